// SPDX-License-Identifier: Apache-2.0
// The AFN engine's implementation choices: the strip refinement equals a whole-frame pass over
// several strips, the AVX-512 and portable kernels agree (where the CPU has AVX-512), and the
// stage FLOP counts that the benchmarks divide by match a count by hand; the AVX-512 row filter
// equals the per-pixel softmax + 7x7 kernel at the borders and with non-finite logits.
#include "afn_random_inputs.h"
#include "cpu/afn_filter_avx512.h"
#include "cpu/isa.h"
#include "methods/afn/fusion.h"
#include "methods/afn/network.h"
#include "methods/afn/random_weights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using afn::Image;
using afn::afnet::Network;

namespace {

/// The network's inputs for these tests (seed 7).
struct Frame : afntest::RandomAfnInputs {
    Frame(int w, int h)
        : RandomAfnInputs(w, h, 7u)
    {
    }
};

struct IsaGuard {
    afn::cpu::Isa saved = afn::cpu::activeIsa();
    ~IsaGuard() { afn::cpu::forceIsa(saved); }
};

} // namespace

TEST(AfnEngine, InputIsToneMappedColoursThenGuidesWithEdgesReplicated)
{
    // 37x21 pads to 40x24: three columns and three rows repeat the last ones.
    Frame f(37, 21);
    Network net;
    net.load(afn::afnet::randomWeights(afn::afnet::Architecture {}));
    net.prepare(f.in);
    const Image& x = net.input();
    ASSERT_EQ(x.width(), 40);
    ASSERT_EQ(x.height(), 24);
    ASSERT_EQ(x.channels(), 13);
    int differ = 0;
    for (int y = 0; y < x.height(); ++y)
        for (int xx = 0; xx < x.width(); ++xx) {
            const int sx = std::min(xx, 36), sy = std::min(y, 20);
            float want[13];
            for (int c = 0; c < 3; ++c) {
                want[c] = afn::afnet::toneMap(f.c1(sx, sy, c));
                want[3 + c] = afn::afnet::toneMap(f.cta(sx, sy, c));
                want[6 + c] = f.albedo(sx, sy, c);
                want[9 + c] = f.normal(sx, sy, c);
            }
            want[12] = f.depth(sx, sy, 0);
            for (int c = 0; c < 13; ++c)
                differ += x(xx, y, c) != want[c];
        }
    EXPECT_EQ(differ, 0);
}

TEST(AfnEngine, StripRefinementEqualsWholeFramePass)
{
    // 150 rows (padded 152): three strips of 64 rows, halos across both inner edges.
    Frame f(24, 150);
    Network net;
    net.load(afn::afnet::randomWeights(afn::afnet::Architecture {}));
    Image o;
    net.runWholeFrame(f.in, o);
    // Whole-frame refinement with the same layers (Conv::run over full images).
    const Image& i = net.fused();
    const Image& x = net.input();
    Image in(i.width(), i.height(), 10), r1, r2, r3;
    for (int y = 0; y < i.height(); ++y)
        for (int xx = 0; xx < i.width(); ++xx) {
            for (int c = 0; c < 3; ++c)
                in(xx, y, c) = afn::afnet::toneMap(i(xx, y, c));
            for (int c = 0; c < 7; ++c)
                in(xx, y, 3 + c) = x(xx, y, 6 + c);
        }
    net.layer(Network::Layer::Ref1).run(nullptr, in, r1, true);
    net.layer(Network::Layer::Ref2).run(nullptr, r1, r2, true);
    net.layer(Network::Layer::Ref3).run(nullptr, r2, r3, false);
    int differ = 0;
    for (int y = 0; y < o.height(); ++y)
        for (int xx = 0; xx < o.width(); ++xx)
            for (int c = 0; c < 3; ++c)
                differ += o(xx, y, c) != i(xx, y, c) + r3(xx, y, c);
    EXPECT_EQ(differ, 0) << "strip refinement differs from the whole-frame pass";
}

TEST(AfnEngine, PortableAndAvx512KernelsAgree)
{
    IsaGuard guard;
    afn::cpu::forceIsa(afn::cpu::Isa::Avx512);
    if (afn::cpu::activeIsa() != afn::cpu::Isa::Avx512)
        GTEST_SKIP() << "this CPU has no AVX-512F: only the portable kernels run here";
    Frame f(72, 40);
    Network net;
    net.load(afn::afnet::randomWeights(afn::afnet::Architecture {}));
    Image fast, portable;
    net.run(f.in, fast);
    afn::cpu::forceIsa(afn::cpu::Isa::Portable);
    net.run(f.in, portable);
    double maxAbs = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < fast.size(); ++k) {
        maxAbs = std::max(maxAbs, double(std::fabs(fast.data()[k] - portable.data()[k])));
        scale = std::max(scale, double(std::fabs(portable.data()[k])));
    }
    std::printf(
        "avx512 vs portable: max abs difference %.3g (outputs up to %.3g)\n", maxAbs, scale);
    // Float rounding only (different summation order in the filtering, exp on 16 lanes).
    EXPECT_LT(maxAbs, 1e-5 * std::max(1.0, scale));
}

TEST(AfnEngine, StageFlopMatchesHandCount)
{
    Frame f(128, 72); // multiples of 8: no padding
    Network net;
    net.load(afn::afnet::randomWeights(afn::afnet::Architecture {}));
    Image o;
    net.prepare(f.in); // sets the size; FLOP depend on nothing else
    const double full = 128.0 * 72.0, half = full / 4, quarter = full / 16;
    // 3x3 conv: 2 * 9 * in * out per output pixel; 1x1: 2 * in * out.
    const double prediction = 2 * 9
        * (13 * 16 * half + 16 * 32 * quarter + 32 * 64 * full / 64 + 96 * 32 * quarter
            + 48 * 24 * half);
    const double filtering = 2 * 24 * 49 * half + 2 * 37 * 50 * full + 2 * 49 * 3 * (full + half);
    const double refinement = 2 * 9 * (10 * 16 + 16 * 16 + 16 * 3) * full;
    EXPECT_DOUBLE_EQ(net.stageFlop(Network::Stage::Prediction), prediction);
    EXPECT_DOUBLE_EQ(net.stageFlop(Network::Stage::Filtering), filtering);
    EXPECT_DOUBLE_EQ(net.stageFlop(Network::Stage::Refinement), refinement);
    // About 24 kFLOP per pixel in all (training/README.md: the network's cost).
    EXPECT_NEAR((prediction + filtering + refinement) / full, 24000.0, 500.0);
}

TEST(AfnEngine, RowFilterMatchesThePerPixelKernelAtBordersTailsAndExtremeLogits)
{
    // cpu::softmaxApplyRowAvx512 (16 pixels per call, planar rows with a zero pad) against the
    // portable softmax + applyKernel on every pixel of a 37 x 9 image: the left, right, top and
    // bottom borders, a 5-pixel tail, and logits that are NaN, +-Inf, +-FLT_MAX, huge and equal.
    // The logits span [-4, 4] and reach the exponentials' clamp (-87) through the extreme ones.
    IsaGuard guard;
    afn::cpu::forceIsa(afn::cpu::Isa::Avx512);
    if (afn::cpu::activeIsa() != afn::cpu::Isa::Avx512)
        GTEST_SKIP() << "this CPU has no AVX-512F: only the portable kernels run here";
    const int w = 37, h = 9, stride = 64;
    Image img(w, h, 3);
    std::uint32_t s = 12345u;
    auto next = [&s] {
        s = s * 1664525u + 1013904223u;
        return static_cast<float>(s >> 8) / 16777216.0f;
    };
    for (std::size_t k = 0; k < img.size(); ++k)
        img.data()[k] = 10.0f * next();
    std::vector<float> logits(static_cast<std::size_t>(w) * stride);
    for (int x = 0; x < w; ++x)
        for (int j = 0; j < 49; ++j)
            logits[x * stride + j] = 8.0f * next() - 4.0f;
    const float inf = std::numeric_limits<float>::infinity();
    logits[1 * stride + 3] = std::nanf("");
    logits[2 * stride + 10] = inf;
    logits[3 * stride + 0] = -inf;
    logits[4 * stride + 48] = FLT_MAX;
    logits[5 * stride + 20] = -FLT_MAX;
    logits[6 * stride + 7] = 1e30f;
    for (int j = 0; j < 49; ++j)
        logits[7 * stride + j] = 2.5f; // a box filter
    for (int j = 0; j < 49; ++j)
        logits[33 * stride + j] = std::nanf(""); // every logit NaN: still a distribution
    // Both exponentials: the Cephes one and the bf16 heads' cheaper one (relative error 2.7e-6).
    for (const bool bf16 : { false, true }) {
        SCOPED_TRACE(bf16 ? "bf16 logits" : "fp32 logits");
        afn::cpu::PlanarRows rows;
        rows.reset(img);
        double maxAbs = 0.0;
        for (int y = 0; y < h; ++y) {
            for (int yy = y - 3; yy <= y + 3; ++yy)
                rows.ensure(yy);
            std::vector<float> fast(3 * w);
            for (int x0 = 0; x0 < w; x0 += 16)
                afn::cpu::softmaxApplyRowAvx512(logits.data() + x0 * stride, stride,
                    std::min(16, w - x0), rows, x0, y, fast.data() + 3 * x0, bf16);
            for (int x = 0; x < w; ++x) {
                float k[49], rgb[3];
                std::copy(logits.begin() + x * stride, logits.begin() + x * stride + 49, k);
                afn::afnet::softmax(k, 49);
                afn::afnet::applyKernel(img, x, y, k, rgb);
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(fast[3 * x + c])) << x << "," << y;
                    maxAbs = std::max(maxAbs, double(std::fabs(fast[3 * x + c] - rgb[c])));
                }
            }
        }
        EXPECT_LT(maxAbs, 1e-5 * 10.0);
        // The box filter at an inner pixel is the mean of its 49 neighbours.
        rows.reset(img);
        for (int yy = 1; yy <= 7; ++yy)
            rows.ensure(yy);
        std::vector<float> out(3 * 16);
        afn::cpu::softmaxApplyRowAvx512(logits.data(), stride, 16, rows, 0, 4, out.data(), bf16);
        double mean = 0.0;
        for (int dy = -3; dy <= 3; ++dy)
            for (int dx = -3; dx <= 3; ++dx)
                mean += img(7 + dx, 4 + dy, 1);
        EXPECT_NEAR(out[3 * 7 + 1], mean / 49.0, 1e-5);
    }
}
