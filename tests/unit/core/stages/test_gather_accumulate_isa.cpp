// SPDX-License-Identifier: Apache-2.0
// The AVX-512 kernels of the gather (filter/gather_avx512.cpp: the copy with the non-finite
// replacement, the colour's negative clamp, the albedo's [0, 1] clamp, the motion's scale) and of
// the accumulation on a static camera's rows (stages/temporal_accumulation_avx512.cpp) give the
// portable path's bits and counts: on buffers wide enough for several 16-value blocks and a tail,
// with NaN, +-inf, -0, negative and out-of-range values, and for the accumulation with histories
// from 1 to the 255 cap, blends that underflow, and blocks where some pixels took other taps. On a
// CPU without AVX-512F both runs take the portable path and the test checks nothing beyond it
// (said in the output).
#include "cpu/isa.h"
#include "filter/filter.h"
#include "isa_scope.h"
#include "stages/temporal_accumulation.h"
#include "stages/temporal_accumulation_avx512.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <map>
#include <vector>

namespace {

using isa_test::haveAvx512;
using isa_test::IsaScope;

using afn::Frame;
using afn::Image;
using afn::cpu::Isa;
using methods_test::Lcg;

constexpr int W = 53, H = 7; // 3 blocks of 16 pixels and a tail; runs of 3 x 53 floats

bool sameBits(float a, float b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

void expectSameBits(const Image& a, const Image& b, const char* what)
{
    ASSERT_EQ(a.width(), b.width()) << what;
    ASSERT_EQ(a.channels(), b.channels()) << what;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < a.channels(); ++c)
                ASSERT_TRUE(sameBits(a(x, y, c), b(x, y, c)))
                    << what << " at " << x << "," << y << " channel " << c << ": " << a(x, y, c)
                    << " vs " << b(x, y, c);
}

/// Values around the gather's thresholds: NaN, +-inf, +-0, negative, above 1, ordinary.
std::vector<float> awkwardValues(int channels, std::uint32_t seed)
{
    Lcg rng { seed };
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> v(static_cast<std::size_t>(W) * H * channels);
    for (float& x : v) {
        const float r = rng.next();
        x = r < -0.9f   ? std::numeric_limits<float>::quiet_NaN()
            : r < -0.8f ? (r < -0.85f ? inf : -inf)
            : r < -0.7f ? -0.0f
            : r < -0.6f ? 0.0f
            : r < -0.4f ? -0.5f * std::fabs(rng.next())
            : r > 0.8f  ? 1.0f + 3.0f * std::fabs(rng.next())
                        : std::fabs(rng.next());
    }
    return v;
}

afn::ImageBinding packed(std::vector<float>& v, int channels)
{
    afn::ImageBinding b;
    b.ptr = v.data();
    b.format = static_cast<AFNFormat>(channels);
    b.width = W;
    b.height = H;
    b.pixelStride = static_cast<std::ptrdiff_t>(channels * sizeof(float));
    b.rowStride = b.pixelStride * W;
    return b;
}

TEST(GatherAccumulateIsa, GatherMatchesThePortablePath)
{
    if (!haveAvx512())
        std::cout << "[ info ] this CPU has no AVX-512F: both runs take the portable path\n";
    std::vector<float> color = awkwardValues(3, 1u), albedo = awkwardValues(3, 2u),
                       normal = awkwardValues(3, 3u), depth = awkwardValues(1, 4u),
                       position = awkwardValues(3, 5u), motion = awkwardValues(2, 6u);
    const std::map<std::string, afn::ImageBinding> images { { AFN_IMAGE_COLOR, packed(color, 3) },
        { AFN_IMAGE_ALBEDO, packed(albedo, 3) }, { AFN_IMAGE_NORMAL, packed(normal, 3) },
        { AFN_IMAGE_DEPTH, packed(depth, 1) }, { AFN_IMAGE_POSITION, packed(position, 3) },
        { AFN_IMAGE_MOTION, packed(motion, 2) } };
    afn::InputConventions conv;
    conv.motionUnits = afn::InputConventions::MotionUnits::Ndc; // sx != sy
    conv.motionYUp = true; // a negative scale: 0 * sy = -0
    Frame v, p;
    afn::InputStats sv, sp;
    {
        IsaScope s(Isa::Avx512);
        afn::gatherFrame(images, conv, v, sv);
    }
    {
        IsaScope s(Isa::Portable);
        afn::gatherFrame(images, conv, p, sp);
    }
    EXPECT_EQ(sv.nonFinite, sp.nonFinite);
    EXPECT_EQ(sv.negative, sp.negative);
    EXPECT_GT(sp.nonFinite, 0);
    EXPECT_GT(sp.negative, 0);
    expectSameBits(v.color, p.color, "color");
    expectSameBits(v.albedo, p.albedo, "albedo");
    expectSameBits(v.normal, p.normal, "normal");
    expectSameBits(v.depth, p.depth, "depth");
    expectSameBits(v.position, p.position, "position");
    expectSameBits(v.motion, p.motion, "motion");
    // The rules themselves, on the portable result: colour >= 0 or -0, albedo in [0, 1], all
    // finite.
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                EXPECT_FALSE(p.color(x, y, c) < 0.0f);
                EXPECT_TRUE(p.albedo(x, y, c) >= 0.0f && p.albedo(x, y, c) <= 1.0f);
                EXPECT_TRUE(std::isfinite(p.position(x, y, c)));
            }
}

/// One frame accumulated by `v` with AVX-512 and by `p` portably; both results compared bit for
/// bit.
void accumulateBoth(const afn::Reprojector& taps, const Image& color, afn::TemporalAccumulator& v,
    afn::TemporalAccumulator& p)
{
    {
        IsaScope s(Isa::Avx512);
        v.accumulate(taps, color);
    }
    {
        IsaScope s(Isa::Portable);
        p.accumulate(taps, color);
    }
    expectSameBits(v.color(), p.color(), "accumulated colour");
    expectSameBits(v.historyLength(), p.historyLength(), "history length");
}

TEST(GatherAccumulateIsa, StaticRowAccumulationMatchesThePortablePath)
{
    for (float alphaMin : { 0.0f, 0.2f }) {
        afn::Reprojector taps;
        afn::TemporalAccumulator v, p;
        v.setSettings({ alphaMin });
        p.setSettings({ alphaMin });
        // Without the history trust, whose cuts would keep the lengths from the cap.
        v.setTrustSettings({ 0.0f });
        p.setTrustSettings({ 0.0f });
        int capped = 0;
        for (int t = 0; t < 300; ++t) { // past the 255 cap
            const Frame f
                = methods_test::staticCameraFrame(W, H, static_cast<std::uint32_t>(1000 + t));
            taps.compute(f);
            accumulateBoth(taps, f.color, v, p);
            Frame geometry = f;
            taps.takeGeometry(geometry);
            for (int x = 0; x < W; ++x)
                capped += p.historyLength()(x, 3, 0) == afn::kMaxHistoryLength;
        }
        EXPECT_GT(capped, 0) << "no history reached the cap";
    }
}

// The same with the history trust on and light jumps (staticCameraFrameWithLightJumps), so that
// blocks of rows the AVX-512 path blends 16 pixels at a time have trust below 1 (its masked alpha
// and length) next to blocks with trust 1.
TEST(GatherAccumulateIsa, StaticRowAccumulationWithHistoryCutsMatchesThePortablePath)
{
    constexpr int kW = 64, kH = 24;
    afn::Reprojector taps;
    afn::TemporalAccumulator v, p;
    v.setSettings({ 0.2f });
    p.setSettings({ 0.2f });
    int cutFrames = 0;
    for (int t = 0; t < 40; ++t) {
        Frame f = methods_test::staticCameraFrameWithLightJumps(
            kW, kH, static_cast<std::uint32_t>(2000 + t), t);
        taps.compute(f);
        accumulateBoth(taps, f.color, v, p);
        cutFrames += p.trust().active();
        Frame geometry = f;
        taps.takeGeometry(geometry);
    }
    EXPECT_GE(cutFrames, 5) << "the brightness jumps did not lower the trust";
    if (!haveAvx512())
        std::cout << "no AVX-512F on this CPU: both runs took the portable path\n";
}

// The trust's sums of two whole blocks from the AVX-512 kernel against HistoryTrust::RowAdder's
// pixel-by-pixel sums, bit for bit, on random colours spanning several orders of magnitude.
TEST(GatherAccumulateIsa, TrustSumsOfTwoBlocksMatchTheRowAdder)
{
    if (!haveAvx512()) {
        std::cout << "no AVX-512F on this CPU: nothing to compare\n";
        return;
    }
    constexpr int kSums = afn::HistoryTrust::kSums;
    Lcg rng { 77 };
    auto u = [&rng] { return 0.5f * (rng.next() + 1.0f); }; // [0, 1)
    for (int round = 0; round < 50; ++round) {
        std::vector<float> c(48), h(48);
        for (int i = 0; i < 48; ++i) {
            c[i] = u() * std::pow(10.0f, u() * 6.0f - 3.0f);
            h[i] = u() * std::pow(10.0f, u() * 6.0f - 3.0f);
        }
        std::vector<float> want(4 * kSums, 0.0f), got(4 * kSums, 0.0f);
        {
            afn::HistoryTrust::RowAdder row(want.data());
            for (int x = 16; x < 32; ++x)
                row.add(x, c.data() + 3 * (x - 16), h.data() + 3 * (x - 16));
        }
        {
            IsaScope s(Isa::Avx512);
            afn::addOwnHistoryTrust16(c.data(), h.data(), got.data() + 2 * kSums);
        }
        for (int k = 0; k < 4 * kSums; ++k)
            ASSERT_TRUE(sameBits(want[k], got[k]))
                << "sum " << k << " round " << round << ": " << want[k] << " vs " << got[k];
    }
}

} // namespace
