// SPDX-License-Identifier: Apache-2.0
// The AFN engine's implementation choices: the strip refinement equals a whole-frame pass over
// several strips, the AVX-512 and portable kernels agree (where the CPU has AVX-512), and the
// stage FLOP counts that the benchmarks divide by match a count by hand.
#include "cpu/isa.h"
#include "methods/afn/network.h"
#include "methods/afn/random_weights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using afn::Image;
using afn::afnet::Network;

namespace {

struct Frame {
    Image c1, cta, albedo, normal, depth;
    afn::afnet::Inputs in;
    Frame(int w, int h)
    {
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        auto fill = [&](Image& img, int c, float scale) {
            img = Image(w, h, c);
            for (std::size_t k = 0; k < img.size(); ++k)
                img.data()[k] = scale * u(rng);
        };
        fill(c1, 3, 4.0f), fill(cta, 3, 2.0f), fill(albedo, 3, 1.0f), fill(normal, 3, 1.0f);
        fill(depth, 1, 1.0f);
        in = { &c1, &cta, &albedo, &normal, &depth };
    }
};

struct IsaGuard {
    afn::cpu::Isa saved = afn::cpu::activeIsa();
    ~IsaGuard() { afn::cpu::forceIsa(saved); }
};

} // namespace

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
