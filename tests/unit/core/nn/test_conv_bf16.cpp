// SPDX-License-Identifier: Apache-2.0
// nn::Conv in bfloat16 (cpu/conv_avx512_bf16.cpp, cpu/conv_amx_bf16.cpp): each kernel (AMX tiles
// where the CPU has them, VDPBF16PS, its emulation) against a double reference of the same
// bf16-rounded operands (the kernel's only error is then fp32 summation) and within bf16's
// rounding of fp32's result, the hardware instruction and its AVX-512F emulation bit for bit
// (where the CPU has AVX512_BF16), whole rows and column chunks the same bits, and fp32 unchanged
// after a switch to bf16 and back. Few-output layers (cpu/conv_few_outputs_bf16.cpp) are checked
// the same way.
#include "afn_test_util.h"
#include "cpu/bf16.h"
#include "cpu/isa.h"
#include "isa_scope.h"
#include "nn/conv.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using afn::Image;
using afn::cpu::fromBf16;
using afn::cpu::toBf16;
using afn::nn::Precision;

namespace {

using afntest::randomImage;
using afntest::randomVec;

float round16(float v)
{
    return fromBf16(toBf16(v));
}

struct Bf16Scope {
    explicit Bf16Scope(afn::cpu::Bf16Mode m)
        : before(afn::cpu::activeBf16Mode())
    {
        afn::cpu::forceBf16Mode(m);
    }
    ~Bf16Scope() { afn::cpu::forceBf16Mode(before); }
    afn::cpu::Bf16Mode before;
};

struct Layer {
    afn::nn::Conv conv;
    std::vector<float> wt, bias;
    int cin = 0, co = 0, k = 0;
};

Layer makeLayer(int cin, int co, int k, unsigned seed)
{
    Layer l;
    l.cin = cin, l.co = co, l.k = k;
    l.wt = randomVec(static_cast<std::size_t>(co) * cin * k * k, seed);
    l.bias = randomVec(co, seed + 1);
    l.conv.load(afntest::parseArchive(
                    { { "c.weight",
                          { static_cast<std::uint32_t>(co), static_cast<std::uint32_t>(cin),
                              static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(k) },
                          l.wt },
                        { "c.bias", { static_cast<std::uint32_t>(co) }, l.bias } }),
        "c", cin);
    return l;
}

/// Double-precision convolution of concat(U(up), same) with every operand (not the bias) rounded
/// to bf16 when `bf16`.
double reference(const Layer& l, const Image* up, const Image& same, int x, int y, int o, bool bf16)
{
    const int cu = up ? up->channels() : 0, r = l.k / 2;
    double acc = l.bias[o];
    for (int ci = 0; ci < l.cin; ++ci)
        for (int ky = 0; ky < l.k; ++ky)
            for (int kx = 0; kx < l.k; ++kx) {
                const int xx = x + kx - r, yy = y + ky - r;
                if (xx < 0 || yy < 0 || xx >= same.width() || yy >= same.height())
                    continue;
                float v = ci < cu ? (*up)(xx / 2, yy / 2, ci) : same(xx, yy, ci - cu);
                float w = l.wt[((static_cast<std::size_t>(o) * l.cin + ci) * l.k + ky) * l.k + kx];
                if (bf16)
                    v = round16(v), w = round16(w);
                acc += static_cast<double>(v) * w;
            }
    return acc;
}

void checkLayer(int cu, int cs, int co, int k, int w, int h, bool relu)
{
    Layer l = makeLayer(cu + cs, co, k, 31u + static_cast<unsigned>(co));
    l.conv.setPrecision(Precision::Bf16);
    ASSERT_EQ(l.conv.precision(), Precision::Bf16);
    const Image up = randomImage((w + 1) / 2, (h + 1) / 2, std::max(cu, 1), 41);
    const Image same = randomImage(w, h, cs, 42);
    const Image* u = cu ? &up : nullptr;
    Image out;
    l.conv.run(u, same, out, relu);
    double worstSame = 0, worstFp32 = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int o = 0; o < co; ++o) {
                double want = reference(l, u, same, x, y, o, true);
                double fp = reference(l, u, same, x, y, o, false);
                if (relu)
                    want = std::max(want, 0.0), fp = std::max(fp, 0.0);
                worstSame = std::max(worstSame, std::abs(out(x, y, o) - want));
                worstFp32 = std::max(worstFp32, std::abs(out(x, y, o) - fp));
            }
    const int taps = k * k * (cu + cs);
    // fp32 sums of `taps` exact products of size <= 1: a few ulps of the sum each.
    EXPECT_LT(worstSame, 4e-7 * taps) << "cin " << cu + cs << " cout " << co << " k " << k;
    // bf16 rounds each operand by up to 2^-9 relatively: the sum moves by about
    // 2^-8 * sqrt(taps) (random signs); 2^-8 * taps is the bound no input can pass.
    EXPECT_LT(worstFp32, std::ldexp(1.0, -8) * taps);
    EXPECT_GT(worstFp32, worstSame) << "bf16 rounding left no trace: the layer ran in fp32";
    // Column chunks (the AFN heads) give the same bits as whole rows.
    std::vector<float> rows(static_cast<std::size_t>(w) * h * co, -7.0f);
    const int mid = w / 3 + 1;
    l.conv.runRows(u, same, 0, h, rows.data(), static_cast<long>(w) * co, co, relu, 0, mid);
    l.conv.runRows(u, same, 0, h, rows.data() + static_cast<std::size_t>(mid) * co,
        static_cast<long>(w) * co, co, relu, mid, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int o = 0; o < co; ++o)
                ASSERT_EQ(rows[(static_cast<std::size_t>(y) * w + x) * co + o], out(x, y, o));
}

class ConvBf16 : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!isa_test::haveAvx512())
            GTEST_SKIP() << "the bf16 engine is part of the AVX-512 kernels";
    }
    isa_test::IsaScope isa { afn::cpu::Isa::Avx512 };
};

} // namespace

TEST(Bf16, RoundsToNearestEvenAndKeepsSpecialValues)
{
    EXPECT_EQ(toBf16(1.0f), 0x3F80);
    EXPECT_EQ(round16(1.0f + std::ldexp(1.0f, -8)), 1.0f); // tie -> even (down)
    EXPECT_EQ(round16(1.0f + 3 * std::ldexp(1.0f, -8)), 1.0f + std::ldexp(1.0f, -6)); // tie up
    EXPECT_EQ(
        round16(1.0f + std::ldexp(1.0f, -8) + std::ldexp(1.0f, -20)), 1.0f + std::ldexp(1.0f, -7));
    EXPECT_EQ(round16(-2.5f), -2.5f);
    EXPECT_TRUE(std::isinf(round16(std::numeric_limits<float>::infinity())));
    EXPECT_TRUE(std::isnan(round16(std::numeric_limits<float>::quiet_NaN())));
    EXPECT_TRUE(std::isnan(round16(-std::numeric_limits<float>::quiet_NaN())));
    EXPECT_TRUE(std::isinf(round16(std::numeric_limits<float>::max()))); // rounds up past max
}

TEST_F(ConvBf16, MatchesTheReferenceOfBf16OperandsOnEveryBlockShape)
{
    for (const auto mode :
        { afn::cpu::Bf16Mode::Amx, afn::cpu::Bf16Mode::Hardware, afn::cpu::Bf16Mode::Emulated }) {
        const Bf16Scope scope(mode);
        SCOPED_TRACE(afn::cpu::bf16ModeName(afn::cpu::activeBf16Mode()));
        checkLayer(0, 13, 16, 3, 37, 9, true); // AFN enc1 (odd input channels)
        checkLayer(16, 32, 32, 3, 30, 8, true); // a decoder (upsampled part)
        checkLayer(24, 13, 50, 1, 45, 4, false); // headTA: 4 vectors, last one partial
        checkLayer(0, 24, 49, 1, 29, 3, false); // head1
        checkLayer(0, 96, 24, 3, 17, 5, true); // C = 96
        checkLayer(0, 10, 16, 3, 33, 7, true); // refinement
        checkLayer(0, 20, 70, 3, 21, 6, false); // two channel blocks (64 + 6)
        checkLayer(0, 16, 3, 3, 37, 6, false); // refinement's last layer (a last block of 5)
        checkLayer(0, 16, 1, 3, 16, 5, false); // albedo trust head (one whole block)
        checkLayer(8, 24, 2, 3, 35, 4, true); // 3 vectors per kernel row, upsampled part
        checkLayer(0, 13, 4, 1, 33, 3, true); // 1x1, a half vector
        checkLayer(0, 16, 2, 5, 19, 7, false); // run-time shape (5x5)
    }
}

TEST_F(ConvBf16, HardwareAndEmulationGiveTheSameBits)
{
    if (!afn::cpu::cpuHasAvx512Bf16())
        GTEST_SKIP() << "this CPU has no AVX512_BF16";
    // With AVX512_BF16 the band is written in bf16 directly, composed per 16-channel chunk from
    // the upsampled and the same input; the emulation fills the fp32 band and rounds it: every
    // composition (chunks of one source, of both, partly zero; 1 to 6 chunks; column windows
    // that start inside the image) must give the same bits.
    struct Shape {
        int cu, cs, co, k, w, h;
    };
    for (const Shape& sh : { Shape { 0, 37, 50, 3, 41, 11 }, Shape { 24, 14, 50, 1, 37, 6 },
             Shape { 32, 16, 24, 3, 23, 9 }, Shape { 64, 32, 32, 3, 19, 7 },
             Shape { 0, 10, 16, 3, 35, 8 }, Shape { 0, 32, 32, 3, 21, 5 },
             Shape { 8, 5, 16, 3, 17, 6 }, Shape { 0, 16, 3, 3, 37, 6 },
             Shape { 8, 24, 2, 3, 35, 4 }, Shape { 0, 13, 4, 1, 33, 3 },
             Shape { 0, 16, 2, 5, 19, 7 } }) {
        SCOPED_TRACE("up " + std::to_string(sh.cu) + " same " + std::to_string(sh.cs) + " k "
            + std::to_string(sh.k));
        Layer l = makeLayer(sh.cu + sh.cs, sh.co, sh.k, 7u + static_cast<unsigned>(sh.cs));
        l.conv.setPrecision(Precision::Bf16);
        const Image up = randomImage((sh.w + 1) / 2, (sh.h + 1) / 2, std::max(sh.cu, 1), 9);
        const Image same = randomImage(sh.w, sh.h, sh.cs, 8);
        const Image* u = sh.cu ? &up : nullptr;
        const int mid = sh.w / 3 + 1;
        std::vector<float> a(static_cast<std::size_t>(sh.w) * sh.h * sh.co);
        std::vector<float> b(a.size());
        for (auto [mode, out] : { std::pair { afn::cpu::Bf16Mode::Hardware, &a },
                 std::pair { afn::cpu::Bf16Mode::Emulated, &b } }) {
            const Bf16Scope s(mode);
            const long row = static_cast<long>(sh.w) * sh.co;
            l.conv.runRows(u, same, 0, sh.h, out->data(), row, sh.co, true, 0, mid);
            l.conv.runRows(u, same, 0, sh.h, out->data() + static_cast<std::size_t>(mid) * sh.co,
                row, sh.co, true, mid, sh.w);
        }
        for (std::size_t i = 0; i < a.size(); ++i)
            ASSERT_EQ(a[i], b[i]) << "at " << i;
    }
}

TEST_F(ConvBf16, Fp32StaysAsItWas)
{
    for (const auto [cin, co] : { std::pair { 13, 16 }, std::pair { 16, 3 } }) {
        Layer l = makeLayer(cin, co, 3, 10);
        const Image same = randomImage(19, 6, cin, 11);
        Image fp32, bf16, again;
        l.conv.run(nullptr, same, fp32, false);
        l.conv.setPrecision(Precision::Bf16);
        ASSERT_EQ(l.conv.precision(), Precision::Bf16);
        l.conv.run(nullptr, same, bf16, false);
        l.conv.setPrecision(Precision::Fp32);
        l.conv.run(nullptr, same, again, false);
        bool differs = false;
        for (std::size_t i = 0; i < fp32.size(); ++i) {
            ASSERT_EQ(fp32.data()[i], again.data()[i]);
            differs = differs || fp32.data()[i] != bf16.data()[i];
        }
        EXPECT_TRUE(differs) << co << " outputs: bf16 left no trace";
    }
}
