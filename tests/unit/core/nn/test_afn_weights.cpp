// SPDX-License-Identifier: Apache-2.0
// The .afnw reader: a hand-built archive, and rejection of every kind of corruption.
#include "afn_test_util.h"
#include "base/exception.h"
#include "nn/weights.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace {

using Bytes = std::vector<unsigned char>;

void put(Bytes& b, std::uint64_t v, int n)
{
    for (int i = 0; i < n; ++i)
        b.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

/// The same archive as training/tests/test_afn_weights.py::test_layout_by_hand:
/// one tensor "a" = [1.5, -2.0], metadata "k=v\n"; data at offset 48, 56 bytes in total.
Bytes handArchive()
{
    Bytes b = { 'A', 'F', 'N', 'W' };
    put(b, 1, 4);
    put(b, 1, 4);
    put(b, 4, 4);
    for (char c : std::string("k=v\n"))
        b.push_back(static_cast<unsigned char>(c));
    put(b, 1, 2);
    b.push_back('a');
    b.push_back(1); // float32
    b.push_back(1); // rank
    put(b, 2, 4);
    put(b, 48, 8);
    put(b, 8, 8);
    while (b.size() < 48)
        b.push_back(0);
    const float v[2] = { 1.5f, -2.0f };
    std::uint32_t bits[2];
    std::memcpy(bits, v, 8);
    put(b, bits[0], 4);
    put(b, bits[1], 4);
    return b;
}

std::string parseError(const Bytes& b)
{
    try {
        afn::nn::WeightsArchive::parse(b.data(), b.size(), "test.afnw");
    } catch (const afn::Exception& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(AfnWeights, ParsesHandBuiltArchive)
{
    const Bytes b = handArchive();
    ASSERT_EQ(b.size(), 56u);
    const auto a = afn::nn::WeightsArchive::parse(b.data(), b.size(), "hand");
    EXPECT_EQ(a.meta("k"), "v");
    EXPECT_EQ(a.meta("missing", "x"), "x");
    const auto& t = a.tensor("a");
    ASSERT_EQ(t.dims, std::vector<std::int64_t>({ 2 }));
    EXPECT_EQ(t.data[0], 1.5f);
    EXPECT_EQ(t.data[1], -2.0f);
    EXPECT_THROW(a.tensor("b"), afn::Exception);
}

TEST(AfnWeights, RejectsEveryTruncation)
{
    const Bytes b = handArchive();
    for (std::size_t n = 0; n < b.size(); ++n) {
        const Bytes cut(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n));
        EXPECT_NE(parseError(cut).find("invalid or corrupted weights"), std::string::npos) << n;
    }
}

TEST(AfnWeights, RejectsBadFields)
{
    Bytes b = handArchive();
    b[0] = 'X';
    EXPECT_NE(parseError(b).find("bad magic"), std::string::npos);
    b = handArchive();
    b[4] = 2;
    EXPECT_NE(parseError(b).find("version 2"), std::string::npos);
    b = handArchive();
    b[23] = 7; // dtype
    EXPECT_NE(parseError(b).find("dtype"), std::string::npos);
    b = handArchive();
    b[29] = 200; // data offset 48 -> 200: outside the file
    EXPECT_NE(parseError(b).find("outside the file"), std::string::npos);
    b = handArchive();
    b[37] = 12; // data size 8 -> 12
    EXPECT_NE(parseError(b).find("does not match"), std::string::npos);
    b = handArchive();
    b[33] = 0xff; // offset with a huge high byte: no overflow in the bounds check
    b[36] = 0xff;
    EXPECT_NE(parseError(b).find("invalid or corrupted weights"), std::string::npos);
    const std::string lfs = "version https://git-lfs.github.com/spec/v1\noid sha256:00\n";
    const Bytes p(lfs.begin(), lfs.end());
    EXPECT_NE(parseError(p).find("Git LFS pointer"), std::string::npos);
    EXPECT_NE(parseError(Bytes()).find("invalid or corrupted weights"), std::string::npos);
}

extern "C" const unsigned char afnTestEmbedded[];
extern "C" const unsigned long long afnTestEmbedded_size;

TEST(AfnWeights, EmbeddedBytesEqualTheFile)
{
    const auto fromFile
        = afntest::loadFile(std::string(AFN_TEST_DATA) + "/afn_parity/weights_fusion.afnw");
    std::ifstream f(
        std::string(AFN_TEST_DATA) + "/afn_parity/weights_fusion.afnw", std::ios::binary);
    const std::vector<char> bytes(
        (std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ASSERT_EQ(afnTestEmbedded_size, bytes.size());
    EXPECT_EQ(std::memcmp(afnTestEmbedded, bytes.data(), bytes.size()), 0);
    const auto a
        = afn::nn::WeightsArchive::parse(afnTestEmbedded, afnTestEmbedded_size, "embedded");
    EXPECT_EQ(a.tensors().size(), fromFile.tensors().size());
    EXPECT_EQ(a.meta("variant"), "fusion");
}
