// SPDX-License-Identifier: Apache-2.0
// The temporal anti-aliasing stage (stages/taa.h) against its definition evaluated per pixel here
// (the 3x3 box and 5-tap cross of the current frame in YCoCg, the bilinear history over in-image
// taps, the clamp, the blend): bit-identical on the portable and the AVX-512 row kernels, on static
// rows (identity reprojection) and moving ones, with and without SVGF's box fallback; a static
// image is a fixed point; without history the output is the current frame; and an edge pixel that
// alternates between two values from frame to frame (a silhouette at 1 spp) flickers less.
#include "isa_scope.h"
#include "stages/taa.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <iostream>

namespace {

using afn::Frame;
using afn::Image;
using afn::PixelTaps;
using afn::cpu::Isa;
using isa_test::haveAvx512;
using isa_test::IsaScope;
using methods_test::Lcg;
using methods_test::makeImage;

constexpr int W = 37, H = 11; // two 16-pixel blocks and a tail

void toYCoCg(const float* c, float* o)
{
    o[0] = 0.25f * c[0] + 0.5f * c[1] + 0.25f * c[2];
    o[1] = 0.5f * c[0] - 0.5f * c[2];
    o[2] = -0.25f * c[0] + 0.5f * c[1] - 0.25f * c[2];
}

/// The definition of stages/taa.h for pixel (x, y), literally.
void referencePixel(const afn::Reprojector& taps, const Image& cur, const Image& history,
    float alpha, int x, int y, float* o)
{
    const float* c = cur.at(x, y);
    const PixelTaps t = taps.taps(x, y);
    float hist[3] = { 0.0f, 0.0f, 0.0f }, ws = 0.0f;
    if (t.onScreen && !t.box) {
        const float bw[4] = { (1.0f - t.fx) * (1.0f - t.fy), t.fx * (1.0f - t.fy),
            (1.0f - t.fx) * t.fy, t.fx * t.fy };
        for (int k = 0; k < 4; ++k) {
            const int hx = t.x0 + (k & 1), hy = t.y0 + (k >> 1);
            if (!(bw[k] > 0.0f) || hx < 0 || hy < 0 || hx >= W || hy >= H)
                continue;
            for (int ch = 0; ch < 3; ++ch)
                hist[ch] += bw[k] * history(hx, hy, ch);
            ws += bw[k];
        }
    }
    if (!(ws > 0.0f)) {
        std::copy(c, c + 3, o);
        return;
    }
    for (float& v : hist)
        v /= ws;
    float boxLo[3], boxHi[3], crossLo[3], crossHi[3];
    std::fill(boxLo, boxLo + 3, FLT_MAX);
    std::fill(crossLo, crossLo + 3, FLT_MAX);
    std::fill(boxHi, boxHi + 3, -FLT_MAX);
    std::fill(crossHi, crossHi + 3, -FLT_MAX);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            float q[3];
            toYCoCg(cur.at(std::clamp(x + dx, 0, W - 1), std::clamp(y + dy, 0, H - 1)), q);
            for (int k = 0; k < 3; ++k) {
                boxLo[k] = std::min(boxLo[k], q[k]);
                boxHi[k] = std::max(boxHi[k], q[k]);
                if (dx == 0 || dy == 0) {
                    crossLo[k] = std::min(crossLo[k], q[k]);
                    crossHi[k] = std::max(crossHi[k], q[k]);
                }
            }
        }
    float hy[3];
    toYCoCg(hist, hy);
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
        const float lo = 0.5f * (boxLo[k] + crossLo[k]), hi = 0.5f * (boxHi[k] + crossHi[k]);
        if (hy[k] < lo || hy[k] > hi) {
            inside = false;
            hy[k] = std::clamp(hy[k], lo, hi);
        }
    }
    if (!inside) {
        hist[0] = hy[0] + hy[1] - hy[2];
        hist[1] = hy[0] + hy[2];
        hist[2] = hy[0] - hy[1] - hy[2];
    }
    for (int k = 0; k < 3; ++k) {
        float v = hist[k] + alpha * (c[k] - hist[k]);
        v = std::fabs(v) < FLT_MIN ? 0.0f : v;
        o[k] = std::max(0.0f, v);
    }
}

/// A frame whose rows below `firstMoving` move by quarter pixels (some off the screen), with
/// positions and normals that reject some taps.
Frame sceneFrame(std::uint32_t seed, int firstMoving)
{
    Lcg rng { seed };
    Frame f;
    f.width = W;
    f.height = H;
    f.color = Image(W, H, 3, 1.0f);
    f.position = makeImage(W, H, 3, [](int x, int y, int c) {
        return c == 0 ? 0.1f * x : c == 1 ? 0.1f * y : 0.0f;
    });
    f.normal = makeImage(W, H, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    f.motion = Image(W, H, 2, 0.0f);
    for (int y = firstMoving; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            f.motion(x, y, 0) = std::round(rng.next() * 8.0f) / 4.0f;
            f.motion(x, y, 1) = std::round(rng.next() * 4.0f) / 4.0f;
            if (rng.next() > 0.8f)
                f.position(x, y, 2) = 0.5f; // rejected by the position test
        }
    f.motion(W - 1, H - 1, 0) = 40.0f; // off the screen
    return f;
}

/// Radiance >= 0 with exact zeros, repeated values and a few large ones.
Image radiance(std::uint32_t seed)
{
    Lcg rng { seed };
    return makeImage(W, H, 3, [&](int, int, int) {
        const float r = rng.next();
        return r < -0.8f ? 0.0f : r > 0.9f ? 20.0f * r : r < -0.6f ? 0.5f : std::fabs(r);
    });
}

bool sameBits(float a, float b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(Taa, MatchesItsPerPixelDefinitionOnBothKernels)
{
    if (!haveAvx512())
        std::cout << "no AVX-512F on this CPU: both runs are portable\n";
    for (bool box : { false, true }) {
        afn::ReprojectSettings s;
        s.boxFallback = box;
        afn::Reprojector taps;
        taps.setSettings(s);
        taps.storeGeometry(sceneFrame(3u, H));
        taps.compute(sceneFrame(5u, 4)); // rows 0-3 static
        const Image cur = radiance(7u), history = radiance(9u);
        Image want(W, H, 3);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                referencePixel(taps, cur, history, 0.2f, x, y, want.at(x, y));
        int clamped = 0, kept = 0, fresh = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                for (int k = 0; k < 3; ++k) {
                    const float c = cur(x, y, k), h = history(x, y, k), o = want(x, y, k);
                    fresh += sameBits(o, c);
                    kept += std::fabs(o - (h + 0.2f * (c - h))) < 1e-6f;
                    clamped += !sameBits(o, c) && std::fabs(o - (h + 0.2f * (c - h))) > 1e-3f;
                }
        EXPECT_GT(clamped, 50); // the scene has every outcome
        EXPECT_GT(kept, 50);
        EXPECT_GT(fresh, 0);
        for (Isa isa : { Isa::Portable, Isa::Avx512 }) {
            IsaScope scope(isa);
            Image got;
            afn::temporalAntialias(taps, cur, history, 0.2f, got);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x)
                    for (int k = 0; k < 3; ++k)
                        ASSERT_TRUE(sameBits(got(x, y, k), want(x, y, k)))
                            << "isa " << static_cast<int>(isa) << " box " << box << " at " << x
                            << "," << y << "," << k << ": " << got(x, y, k) << " vs "
                            << want(x, y, k);
        }
    }
}

TEST(Taa, AStaticImageIsAFixedPoint)
{
    afn::Reprojector taps;
    taps.storeGeometry(sceneFrame(3u, H));
    taps.compute(sceneFrame(3u, H));
    const Image cur = radiance(11u);
    for (Isa isa : { Isa::Portable, Isa::Avx512 }) {
        IsaScope scope(isa);
        Image out;
        afn::temporalAntialias(taps, cur, cur, 0.2f, out);
        for (std::size_t i = 0; i < cur.size(); ++i)
            ASSERT_TRUE(sameBits(out.data()[i], cur.data()[i])) << i;
    }
}

TEST(Taa, WithoutHistoryTheOutputIsTheCurrentFrame)
{
    afn::Reprojector taps; // no stored geometry: no history
    taps.compute(sceneFrame(3u, H));
    ASSERT_FALSE(taps.hasHistory());
    const Image cur = radiance(13u), history = radiance(15u);
    Image out;
    afn::temporalAntialias(taps, cur, history, 0.2f, out);
    EXPECT_EQ(std::memcmp(out.data(), cur.data(), cur.size() * sizeof(float)), 0);
    // A history of another size is not used either.
    afn::Reprojector withHistory;
    withHistory.storeGeometry(sceneFrame(3u, H));
    withHistory.compute(sceneFrame(3u, H));
    afn::temporalAntialias(withHistory, cur, Image(W - 1, H, 3, 1.0f), 0.2f, out);
    EXPECT_EQ(std::memcmp(out.data(), cur.data(), cur.size() * sizeof(float)), 0);
}

TEST(Taa, AnAlternatingEdgePixelFlickersLess)
{
    // A static camera; column 18 alternates between the dark left side (0.1) and the bright right
    // side (0.9) from frame to frame, as a silhouette pixel does when the renderer jitters its one
    // sample. TAA keeps it within the neighbourhood's range and averages it over time.
    const Frame geometry = sceneFrame(3u, H);
    afn::Reprojector taps;
    afn::TemporalAntialiasing taa;
    Image spare;
    float inputSwing = 0.0f, outputSwing = 0.0f, previous = -1.0f, previousInput = -1.0f;
    for (int frame = 0; frame < 12; ++frame) {
        if (frame > 0)
            taps.storeGeometry(geometry);
        taps.compute(geometry);
        const Image cur = makeImage(W, H, 3, [&](int x, int, int) {
            return x < 18 ? 0.1f : x > 18 ? 0.9f : (frame % 2 ? 0.9f : 0.1f);
        });
        const float out = taa.apply(taps, cur, afn::kTaaAlpha, spare)(18, 5, 0);
        if (frame >= 6) { // after the history has settled
            inputSwing = std::max(inputSwing, std::fabs(cur(18, 5, 0) - previousInput));
            outputSwing = std::max(outputSwing, std::fabs(out - previous));
        }
        previous = out;
        previousInput = cur(18, 5, 0);
        EXPECT_GE(out, 0.1f);
        EXPECT_LE(out, 0.9f);
    }
    EXPECT_LT(outputSwing, 0.25f * inputSwing);
}

} // namespace
