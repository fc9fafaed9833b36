// SPDX-License-Identifier: Apache-2.0
// Reprojection (lib/core/reproject): whole and fractional translations via motion vectors and via
// world positions + cameras reproject the previous image onto the current one; acceptance tests
// (position, normal, depth) reset disoccluded pixels.
#include "stages/reproject.h"
#include "stages/temporal_accumulation.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using afn::Frame;
using afn::Image;
using afn::Reprojector;
using methods_test::makeImage;

constexpr int W = 16, H = 16;

/// A smooth test function of continuous world coordinates.
float smooth(float x, float y)
{
    return 2.0f + std::sin(0.2f * x) + std::cos(0.15f * y);
}

Frame baseFrame()
{
    Frame f;
    f.width = W;
    f.height = H;
    f.color = Image(W, H, 3, 1.0f);
    return f;
}

/// Frame k of a camera moving by `shift` over a static plane: pixel (x, y) sees world point
/// (x + 0.5 - cx, y + 0.5 - cy, 0) whose value is smooth(world point).
Frame planeFrame(float cx, float cy, bool withMotion, float mx, float my, bool withCamera)
{
    Frame f = baseFrame();
    f.color = makeImage(W, H, 3, [&](int x, int y, int) {
        return smooth(static_cast<float>(x) + 0.5f - cx, static_cast<float>(y) + 0.5f - cy);
    });
    if (withMotion)
        f.motion = makeImage(W, H, 2, [&](int, int, int c) { return c == 0 ? mx : my; });
    if (withCamera) {
        f.position = makeImage(W, H, 3, [&](int x, int y, int c) {
            return c == 0 ? static_cast<float>(x) + 0.5f - cx
                : c == 1  ? static_cast<float>(y) + 0.5f - cy
                          : 0.0f;
        });
        const auto m = methods_test::shiftedCamera(W, H, cx, cy);
        f.camera.valid = true;
        std::copy(m.begin(), m.end(), f.camera.viewProjection.begin());
    }
    return f;
}

/// Reproject frame 0 (camera at 0) into frame 1 (camera at (cx, cy)) and compare the gathered
/// previous colour with the current colour. Returns the max error over pixels with history and
/// checks that pixels whose source lies outside the image have none.
float reprojectionError(float cx, float cy, bool viaCamera)
{
    Frame f0 = planeFrame(0, 0, !viaCamera, 0, 0, viaCamera);
    Frame f1 = planeFrame(cx, cy, !viaCamera, -cx, -cy, viaCamera);
    if (viaCamera)
        f1.prevCamera = f0.camera;
    Reprojector r;
    r.compute(f0);
    r.storeGeometry(f0);
    r.compute(f1);
    float maxErr = 0.0f;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float prev[3];
            const float ws = afn::gatherHistory<3>(r.taps(x, y), f0.color, prev);
            const float sx = static_cast<float>(x) - cx, sy = static_cast<float>(y) - cy;
            const bool inside = sx >= 0.0f && sy >= 0.0f && sx <= W - 1 && sy <= H - 1;
            if (!inside) {
                // The bilinear footprint leaves the image: at least one tap is gone.
                continue;
            }
            EXPECT_GT(ws, 0.0f) << x << "," << y;
            for (int c = 0; c < 3; ++c)
                maxErr = std::fmax(maxErr, std::fabs(prev[c] - f1.color(x, y, c)));
        }
    // Pixels whose whole bilinear footprint is outside have no history.
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (static_cast<float>(x) - cx <= -1.0f || static_cast<float>(y) - cy <= -1.0f) {
                float prev[3];
                EXPECT_EQ(afn::gatherHistory<3>(r.taps(x, y), f0.color, prev), 0.0f)
                    << x << "," << y;
            }
    return maxErr;
}

// Interpolation error bound of bilinear interpolation of smooth(): h^2/8 * (|f_xx| + |f_yy|) with
// h = 1, |f_xx| <= 0.04, |f_yy| <= 0.0225, plus float rounding.
constexpr float kBilinearBound = (0.04f + 0.0225f) / 8.0f + 1e-5f;

TEST(MethodsReproject, WholePixelShiftViaMotionIsExact)
{
    EXPECT_EQ(reprojectionError(2.0f, 1.0f, false), 0.0f);
    EXPECT_EQ(reprojectionError(-3.0f, 2.0f, false), 0.0f);
}

TEST(MethodsReproject, FractionalShiftViaMotionWithinInterpolationError)
{
    const float e = reprojectionError(0.5f, 0.25f, false);
    EXPECT_LT(e, kBilinearBound);
    EXPECT_GT(e, 0.0f); // it really interpolated
}

TEST(MethodsReproject, WholePixelShiftViaPositionsAndCameraIsExact)
{
    EXPECT_EQ(reprojectionError(2.0f, 1.0f, true), 0.0f);
    EXPECT_EQ(reprojectionError(-1.0f, -2.0f, true), 0.0f);
}

TEST(MethodsReproject, FractionalShiftViaPositionsAndCameraWithinInterpolationError)
{
    EXPECT_LT(reprojectionError(0.5f, 0.25f, true), kBilinearBound);
    EXPECT_LT(reprojectionError(-1.75f, 0.5f, true), kBilinearBound);
}

TEST(MethodsReproject, PixelOffsetOfCurrentFrameShiftsTheLookup)
{
    // BMFR: pix = uv * (W, H) - (off.x, 1 - off.y) with the CURRENT frame's offset. An offset of
    // (0.25, 0.75) instead of (0.5, 0.5) moves the lookup by (+0.25, +0.25) pixels.
    Frame f0 = planeFrame(0, 0, false, 0, 0, true);
    Frame f1 = planeFrame(0, 0, false, 0, 0, true);
    f1.prevCamera = f0.camera;
    f1.camera.pixelOffset = { 0.25f, 0.75f };
    Reprojector r;
    r.storeGeometry(f0);
    r.compute(f1);
    const afn::PixelTaps& t = r.taps(5, 7);
    EXPECT_EQ(t.x0, 5);
    EXPECT_EQ(t.y0, 7);
    EXPECT_FLOAT_EQ(t.fx, 0.25f);
    EXPECT_FLOAT_EQ(t.fy, 0.25f);
}

/// Static frames where a square [4, 8)^2 changes in `which` buffer between frame 0 and frame 1.
void expectSquareReset(const char* which)
{
    Frame f0 = baseFrame(), f1 = baseFrame();
    const std::string w = which;
    auto inSquare = [](int x, int y) { return x >= 4 && x < 8 && y >= 4 && y < 8; };
    if (w == "position") {
        f0.position = makeImage(W, H, 3, [](int x, int y, int c) {
            return c == 0 ? x : c == 1 ? y : 0.0f;
        });
        f1.position = makeImage(W, H, 3, [&](int x, int y, int c) {
            return c == 0 ? x : c == 1 ? y : (inSquare(x, y) ? -5.0f : 0.0f); // an object appears
        });
    } else if (w == "normal") {
        f0.normal = Image(W, H, 3, 0.0f);
        f1.normal = Image(W, H, 3, 0.0f);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                f0.normal(x, y, 2) = 1.0f;
                f1.normal(x, y, inSquare(x, y) ? 0 : 2) = 1.0f; // 90 degrees: squared distance 2
            }
    } else {
        f0.depth = Image(W, H, 1, 10.0f);
        f1.depth
            = makeImage(W, H, 1, [&](int x, int y, int) { return inSquare(x, y) ? 5.0f : 10.5f; });
    }
    Reprojector r;
    afn::TemporalAccumulator ta;
    r.compute(f0);
    ta.accumulate(r, f0.color);
    r.storeGeometry(f0);
    r.compute(f1);
    ta.accumulate(r, f1.color);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            EXPECT_EQ(ta.historyLength()(x, y, 0), inSquare(x, y) ? 1.0f : 2.0f)
                << w << " " << x << "," << y;
}

TEST(MethodsReproject, DisoccludedPixelsResetHistoryByPosition)
{
    expectSquareReset("position");
}
TEST(MethodsReproject, DisoccludedPixelsResetHistoryByNormal)
{
    expectSquareReset("normal");
}
TEST(MethodsReproject, DisoccludedPixelsResetHistoryByRelativeDepth)
{
    expectSquareReset("depth");
}

TEST(MethodsReproject, PositionLimitIsScaleInvariant)
{
    // The same geometry scaled by 10 must give the same acceptance with the same limit.
    for (float scale : { 1.0f, 10.0f, 0.01f }) {
        Frame f0 = baseFrame(), f1 = baseFrame();
        f0.position = makeImage(W, H, 3, [&](int x, int y, int c) {
            return scale * (c == 0 ? x : c == 1 ? y : 0.0f);
        });
        // Frame 1: columns 2-4 moved by 3 footprints (accepted, limit 4), 8-10 by 5 (rejected).
        f1.position = makeImage(W, H, 3, [&](int x, int y, int c) {
            const float dz = (x >= 2 && x <= 4) ? 3.0f : (x >= 8 && x <= 10) ? 5.0f : 0.0f;
            return scale * (c == 0 ? x : c == 1 ? y : dz);
        });
        Reprojector r;
        r.storeGeometry(f0);
        r.compute(f1);
        EXPECT_NE(r.taps(3, 5).mask & 1u, 0u) << scale;
        EXPECT_EQ(r.taps(9, 5).mask & 1u, 0u) << scale;
        EXPECT_NE(r.taps(12, 5).mask & 1u, 0u) << scale;
    }
}

TEST(MethodsReproject, AbsolutePositionLimitIsBmfrsStrictTest)
{
    Frame f0 = baseFrame(), f1 = baseFrame();
    f0.position = Image(W, H, 3, 0.0f);
    f1.position
        = makeImage(W, H, 3, [](int x, int, int c) { return c == 2 && x == 5 ? 0.041f : 0.0f; });
    f1.position(7, 2, 2) = 0.039f;
    afn::ReprojectSettings s;
    s.positionLimitSquared = 0.0016f; // sponza: 0.04^2, strict
    Reprojector r;
    r.setSettings(s);
    r.storeGeometry(f0);
    r.compute(f1);
    EXPECT_EQ(r.taps(5, 3).mask & 1u, 0u); // 0.041^2 > 0.0016
    EXPECT_NE(r.taps(7, 2).mask & 1u, 0u); // 0.039^2 < 0.0016
    EXPECT_NE(r.taps(1, 1).mask & 1u, 0u);
}

TEST(MethodsReproject, MotionOnlyAcceptsEveryInImageTap)
{
    Frame f0 = planeFrame(0, 0, true, 0, 0, false);
    Frame f1 = planeFrame(0, 0, true, 0.5f, -0.5f, false);
    Reprojector r;
    r.storeGeometry(f0);
    r.compute(f1);
    for (int y = 1; y < H; ++y)
        for (int x = 0; x < W - 1; ++x)
            EXPECT_EQ(r.taps(x, y).mask, 0xFu) << x << "," << y;
    EXPECT_EQ(r.taps(W - 1, 3).mask, 0x5u); // right taps outside
    EXPECT_EQ(r.taps(4, 0).mask, 0xCu); // top taps outside
}

TEST(MethodsReproject, SvgfBoxFallbackFindsHistoryWhenBilinearTapsFail)
{
    Frame f0 = baseFrame(), f1 = baseFrame();
    f0.depth = Image(W, H, 1, 10.0f);
    f1.depth = Image(W, H, 1, 10.0f);
    f0.depth(6, 6, 0) = 20.0f; // the bilinear tap of pixel (6, 6) (static: only that tap) fails
    afn::ReprojectSettings s;
    s.boxFallback = true;
    Reprojector r;
    r.setSettings(s);
    r.storeGeometry(f0);
    r.compute(f1);
    const afn::PixelTaps& t = r.taps(6, 6);
    EXPECT_EQ(t.box, 1);
    EXPECT_EQ(t.mask, 0x1EFu); // all 9 but the centre (bit 4)
    EXPECT_EQ(r.taps(7, 7).box, 0);
}

} // namespace
