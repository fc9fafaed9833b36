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
#include "methods/svgf/kernels.h"
#include "stages/reproject.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>

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

} // namespace
