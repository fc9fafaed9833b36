// SPDX-License-Identifier: Apache-2.0
// SVGF's temporal integration on a static camera's rows: the AVX-512 path
// (methods/svgf/integrate_avx512.cpp, 16 pixels whose own previous pixel was accepted) gives the
// per-pixel path's bits in all seven integrated planes (colour, luminance, both moments, history
// length), over 300 frames (past the 255 cap on the history length), on a frame wide enough for
// three 16-pixel blocks and a tail, with pixels that move (their history restarts, so blocks mix
// both paths), black pixels, and values whose blend underflows below FLT_MIN. On a CPU without
// AVX-512F both runs take the per-pixel path and the test says so. The same with the history
// trust cutting some blocks.
#include "isa_scope.h"
#include "methods/svgf/denoiser.h"
#include "methods/svgf/integrate_avx512.h"
#include "methods/svgf/kernels.h"
#include "stages/history_trust.h"
#include "stages/reproject.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <vector>

namespace {

using afn::Frame;
using afn::Image;
using afn::cpu::Isa;
using isa_test::IsaScope;

constexpr int W = 53, H = 7;

/// One frame (w x h) processed by `vector` with AVX-512 and by `perPixel` portably; their seven
/// integrated planes compared bit for bit.
void processBoth(const Frame& f, const afn::Reprojector& taps, afn::svgf::Denoiser& vector,
    afn::svgf::Denoiser& perPixel, int t)
{
    Image out;
    {
        IsaScope s(Isa::Avx512);
        vector.process(f, f.color, taps, out);
    }
    {
        IsaScope s(Isa::Portable);
        perPixel.process(f, f.color, taps, out);
    }
    const afn::svgf::Planes& a = vector.integrated();
    const afn::svgf::Planes& b = perPixel.integrated();
    for (int k = 0; k < afn::svgf::kIntegratedPlanes; ++k)
        for (int y = 0; y < f.height; ++y)
            ASSERT_EQ(std::memcmp(a.row(k, y), b.row(k, y), f.width * sizeof(float)), 0)
                << "plane " << k << " row " << y << " frame " << t;
}

TEST(SvgfIntegrate, StaticRowsMatchThePerPixelPath)
{
    if (!isa_test::haveAvx512())
        std::cout << "[ NOTE ] no AVX-512F: both runs take the per-pixel path\n";
    for (const float alpha : { 0.05f, 0.2f }) {
        afn::svgf::Settings settings;
        settings.alpha = alpha;
        settings.momentsAlpha = 0.2f;
        settings.feedbackTap = -1; // the colour history is the integration, not an à-trous output
        afn::svgf::Denoiser vector, perPixel;
        vector.setSettings(settings);
        perPixel.setSettings(settings);
        // Without the history trust, whose cuts would keep the lengths from the cap.
        vector.setTrustSettings({ 0.0f });
        perPixel.setTrustSettings({ 0.0f });
        afn::Reprojector taps;
        int capped = 0;
        for (int t = 0; t < 300; ++t) {
            Frame f = methods_test::staticCameraFrame(W, H, static_cast<std::uint32_t>(7000 + t));
            taps.compute(f);
            processBoth(f, taps, vector, perPixel, t);
            if (::testing::Test::HasFatalFailure())
                return;
            for (int x = 0; x < W; ++x)
                capped += perPixel.integrated().row(afn::svgf::kHistoryLength, 3)[x] == 255.0f;
            taps.takeGeometry(f);
        }
        EXPECT_GT(capped, 0) << "no history reached the cap";
    }
}

// With the history trust on and light jumps (staticCameraFrameWithLightJumps), so that 16-pixel
// blocks the AVX-512 path integrates have trust below 1 (raised alphas, a shortened length
// rounded up) beside blocks with trust 1.
TEST(SvgfIntegrate, StaticRowsWithHistoryCutsMatchThePerPixelPath)
{
    constexpr int kW = 64, kH = 24;
    afn::svgf::Settings settings;
    settings.feedbackTap = -1;
    afn::svgf::Denoiser vector, perPixel;
    vector.setSettings(settings);
    perPixel.setSettings(settings);
    afn::Reprojector taps;
    int cutFrames = 0;
    for (int t = 0; t < 40; ++t) {
        Frame f = methods_test::staticCameraFrameWithLightJumps(
            kW, kH, static_cast<std::uint32_t>(9000 + t), t);
        taps.compute(f);
        processBoth(f, taps, vector, perPixel, t);
        if (::testing::Test::HasFatalFailure())
            return;
        cutFrames += perPixel.trust().active();
        taps.takeGeometry(f);
    }
    EXPECT_GE(cutFrames, 5) << "the brightness jumps did not lower the trust";
}

// The history trust's sums of two whole blocks from the AVX-512 kernel (the history colour
// scaled to its first moment's luminance) against the rule added pixel by pixel with
// HistoryTrust::RowAdder, bit for bit: random values over six orders of magnitude, some black
// or NaN luminances (scale 1).
TEST(SvgfIntegrate, TrustSumsOfTwoBlocksMatchTheRowAdder)
{
    if (!isa_test::haveAvx512()) {
        std::cout << "[ NOTE ] no AVX-512F: nothing to compare\n";
        return;
    }
    constexpr int kSums = afn::HistoryTrust::kSums;
    methods_test::Lcg rng { 5150u };
    auto u = [&rng] { return 0.5f * (rng.next() + 1.0f); }; // [0, 1)
    for (int round = 0; round < 50; ++round) {
        std::vector<float> c(48), planes[4];
        for (float& v : c)
            v = u() * std::pow(10.0f, u() * 6.0f - 3.0f);
        for (auto& p : planes) {
            p.resize(16);
            for (float& v : p)
                v = u() * std::pow(10.0f, u() * 6.0f - 3.0f);
        }
        planes[0][3] = planes[1][3] = planes[2][3] = 0.0f; // black: scale 1
        planes[1][7] = std::nanf(""); // NaN luminance: scale 1
        std::vector<float> want(4 * kSums, 0.0f), got(4 * kSums, 0.0f);
        {
            afn::HistoryTrust::RowAdder row(want.data());
            for (int i = 0; i < 16; ++i) {
                const float l
                    = 0.2126f * planes[0][i] + 0.7152f * planes[1][i] + 0.0722f * planes[2][i];
                const float s = l > 0.0f ? planes[3][i] / l : 1.0f;
                const float h[3] = { planes[0][i] * s, planes[1][i] * s, planes[2][i] * s };
                row.add(16 + i, c.data() + 3 * i, h);
            }
        }
        const float* prev[4]
            = { planes[0].data(), planes[1].data(), planes[2].data(), planes[3].data() };
        {
            IsaScope s(Isa::Avx512);
            afn::svgf::addOwnTrust16(c.data(), prev, got.data() + 2 * kSums);
        }
        for (int k = 0; k < 4 * kSums; ++k)
            ASSERT_EQ(std::memcmp(&want[k], &got[k], sizeof(float)), 0)
                << "sum " << k << " round " << round << ": " << want[k] << " vs " << got[k];
    }
}

} // namespace
