// SPDX-License-Identifier: Apache-2.0
// The CUDA engine's layouts on the CPU (built without CUDA too): half-precision conversion,
// channel and frame padding, the packed weights against the layer's own, and the fragment
// coordinates of fragment.h against the PTX ISA's definition.
#include "afn_test_util.h"
#include "cuda/fragment.h"
#include "cuda/tensor_layout.h"
#include "nn/conv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <set>

using namespace afn::cuda;

namespace {

float bitsToFloat(std::uint32_t u)
{
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

/// A conv layer with random weights (PyTorch order) of the given shape.
afn::nn::Conv randomConv(int out, int in, int k, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    afntest::NamedTensor w { "l.weight",
        { std::uint32_t(out), std::uint32_t(in), std::uint32_t(k), std::uint32_t(k) }, {} };
    afntest::NamedTensor b { "l.bias", { std::uint32_t(out) }, {} };
    for (int i = 0; i < out * in * k * k; ++i)
        w.data.push_back(u(rng));
    for (int i = 0; i < out; ++i)
        b.data.push_back(u(rng));
    afn::nn::Conv conv;
    conv.load(afntest::parseArchive({ w, b }), "l", in, out);
    return conv;
}

} // namespace

TEST(CudaLayout, HalfConversionKnownValues)
{
    EXPECT_EQ(floatToHalf(0.0f), 0x0000);
    EXPECT_EQ(floatToHalf(-0.0f), 0x8000);
    EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
    EXPECT_EQ(floatToHalf(-2.0f), 0xc000);
    EXPECT_EQ(floatToHalf(65504.0f), 0x7bff);
    EXPECT_EQ(floatToHalf(65519.0f), 0x7bff); // below the rounding boundary
    EXPECT_EQ(floatToHalf(65520.0f), 0x7c00); // rounds to infinity
    EXPECT_EQ(floatToHalf(1e10f), 0x7c00);
    EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -14)), 0x0400); // smallest normal
    EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -24)), 0x0001); // smallest subnormal
    EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -25)), 0x0000); // tie to even: 0
    EXPECT_EQ(floatToHalf(std::ldexp(1.5f, -25)), 0x0001);
    EXPECT_EQ(floatToHalf(std::ldexp(3.0f, -25)), 0x0002); // 1.5 subnormal steps: tie to even 2
    // Ties between normals round to even: 1 + 2^-11 lies halfway between 1 and 1 + 2^-10.
    EXPECT_EQ(floatToHalf(1.0f + std::ldexp(1.0f, -11)), 0x3c00);
    EXPECT_EQ(floatToHalf(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3c02);
    EXPECT_EQ(floatToHalf(1.0f + std::ldexp(1.0f, -11) + std::ldexp(1.0f, -20)), 0x3c01);
    EXPECT_EQ(floatToHalf(std::numeric_limits<float>::infinity()), 0x7c00);
    EXPECT_EQ(floatToHalf(-std::numeric_limits<float>::infinity()), 0xfc00);
    EXPECT_TRUE(std::isnan(halfToFloat(floatToHalf(std::nanf("")))));
    EXPECT_TRUE(std::isnan(halfToFloat(0xffff))); // the poison pattern of the tests
}

TEST(CudaLayout, HalfConversionRoundTripsAndRoundsToNearest)
{
    for (std::uint32_t h = 0; h < 0x10000; ++h) {
        const float f = halfToFloat(static_cast<std::uint16_t>(h));
        if (std::isnan(f))
            continue;
        ASSERT_EQ(floatToHalf(f), h) << std::hex << h;
    }
    // Every float between two neighbouring positive halves goes to the nearer one.
    std::mt19937 rng(3);
    std::uniform_int_distribution<std::uint32_t> bits(0u, 0x477fe000u);
    for (int i = 0; i < 200000; ++i) {
        const float f = bitsToFloat(bits(rng));
        const std::uint16_t h = floatToHalf(f);
        const double v = halfToFloat(h);
        const double below = h > 0 ? halfToFloat(static_cast<std::uint16_t>(h - 1)) : -1.0;
        const double above = halfToFloat(static_cast<std::uint16_t>(h + 1));
        ASSERT_LE(std::fabs(v - f), std::fabs(below - f)) << f;
        ASSERT_LE(std::fabs(v - f), std::fabs(above - f)) << f;
    }
}

TEST(CudaLayout, PaddingOfChannelsTilesAndFrames)
{
    EXPECT_EQ(channelStride(0), 0);
    EXPECT_EQ(channelStride(1), 16);
    EXPECT_EQ(channelStride(13), 16);
    EXPECT_EQ(channelStride(16), 16);
    EXPECT_EQ(channelStride(24), 32);
    EXPECT_EQ(channelStride(96), 96);
    EXPECT_EQ(chunkCount(37), 3);
    EXPECT_EQ(tileCount(3), 1);
    EXPECT_EQ(tileCount(49), 7);
    EXPECT_EQ(tileCount(50), 7);
    EXPECT_EQ(tileCount(64), 8);
    EXPECT_EQ(paddedSize(1), 8);
    EXPECT_EQ(paddedSize(720), 720);
    EXPECT_EQ(paddedSize(1081), 1088);
}

TEST(CudaLayout, PackedWeightsMatchTheLayer)
{
    // A concat layer (up 24 + same 13 channels, headTA-like) and a 3x3 layer with odd widths.
    struct Case {
        int out, in, k, up;
    };
    for (const Case c : { Case { 50, 37, 1, 24 }, Case { 12, 28, 3, 16 }, Case { 3, 8, 3, 0 } }) {
        const afn::nn::Conv conv = randomConv(c.out, c.in, c.k, 7);
        const PackedConv p = packConv(conv, c.up);
        ASSERT_EQ(p.kChunks(), chunkCount(c.up) + chunkCount(c.in - c.up));
        ASSERT_EQ(p.weights.size(), std::size_t(c.k * c.k) * p.kChunks() * p.tiles() * 8 * 8);
        ASSERT_EQ(p.bias.size(), std::size_t(p.tiles()) * 8);
        std::set<std::size_t> seen;
        for (int tap = 0; tap < c.k * c.k; ++tap)
            for (int kc = 0; kc < p.kChunks(); ++kc)
                for (int n = 0; n < p.tiles() * 8; ++n)
                    for (int w = 0; w < 8; ++w) {
                        const std::size_t i
                            = packedWeightIndex(tap, kc, n, w, p.kChunks(), p.tiles());
                        ASSERT_TRUE(seen.insert(i).second) << "index used twice";
                        for (int e = 0; e < 2; ++e) {
                            const int k = 2 * w + e;
                            const bool fromUp = kc < p.upChunks();
                            const int local = (fromUp ? kc : kc - p.upChunks()) * 16 + k;
                            const int ci = fromUp ? local : c.up + local;
                            const bool real
                                = n < c.out && (fromUp ? local < c.up : local < c.in - c.up);
                            const float want = real
                                ? conv.paddedWeights()[(std::size_t(tap) * c.in + ci)
                                        * conv.paddedOutChannels()
                                    + n]
                                : 0.0f;
                            const std::uint16_t h
                                = static_cast<std::uint16_t>(p.weights[i] >> (16 * e));
                            ASSERT_EQ(h, floatToHalf(want))
                                << tap << " " << kc << " " << n << " " << k;
                        }
                    }
        EXPECT_EQ(seen.size(), p.weights.size());
        for (int n = 0; n < p.tiles() * 8; ++n)
            EXPECT_EQ(p.bias[n], n < c.out ? conv.paddedBias()[n] : 0.0f);
    }
}

TEST(CudaLayout, FragmentCoordinatesFollowThePtxLayout)
{
    // PTX ISA, mma.m16n8k16 (.f16): groupID = lane >> 2, threadID_in_group = lane % 4;
    // A: a0,a1 row groupID, a2,a3 row groupID+8, a4..a7 the same rows 8 columns further, columns
    // threadID_in_group * 2 + (i & 1); B: b0,b1 rows threadID_in_group * 2 + (i & 1), b2,b3 8
    // rows further, column groupID; C: c0,c1 row groupID, c2,c3 row groupID + 8.
    std::set<int> a, b, c;
    for (int lane = 0; lane < 32; ++lane) {
        const int gid = lane >> 2, tig = lane % 4;
        for (int reg = 0; reg < 4; ++reg) {
            const int element = 2 * reg; // a0, a2, a4, a6: the low halves of the 4 registers
            const int row = (element < 2 || (element >= 4 && element < 6)) ? gid : gid + 8;
            const int col = tig * 2 + (element & 1) + (element >= 4 ? 8 : 0);
            EXPECT_EQ(Fragment::aRow(lane, reg), row) << lane << " " << reg;
            EXPECT_EQ(Fragment::aCol(lane, reg), col) << lane << " " << reg;
            a.insert(row * 16 + col);
        }
        for (int reg = 0; reg < 2; ++reg) {
            EXPECT_EQ(Fragment::bRow(lane, reg), tig * 2 + 8 * reg);
            EXPECT_EQ(Fragment::bCol(lane), gid);
            b.insert(Fragment::bRow(lane, reg) * 8 + Fragment::bCol(lane));
        }
        for (int i = 0; i < 4; ++i) {
            EXPECT_EQ(Fragment::cRow(lane, i), i < 2 ? gid : gid + 8);
            EXPECT_EQ(Fragment::cCol(lane, i), tig * 2 + (i & 1));
            c.insert(Fragment::cRow(lane, i) * 8 + Fragment::cCol(lane, i));
        }
    }
    EXPECT_EQ(a.size(), 128u); // every even (row, column) pair start of the 16 x 16 tile once
    EXPECT_EQ(b.size(), 64u);
    EXPECT_EQ(c.size(), 128u);
}
