// SPDX-License-Identifier: Apache-2.0
// The reprojection's fast paths give the taps of its documented rule (stages/reproject.h): a
// literal per-pixel evaluation written here (every tap of positive weight tested, the footprint
// computed for every pixel, the 3x3 box fallback) against the stage's compact storage, identity
// rows (zero motion: a static camera) and lazy footprint; and a static row gives the same taps
// and the same "ta" output as the general path of a moving row.
#include "stages/reproject.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using afn::Frame;
using afn::Image;
using afn::PixelTaps;
using methods_test::makeImage;

constexpr int W = 24, H = 12;

float dist2(const float* a, const float* b)
{
    const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/// The rule of stages/reproject.h, literally, for frames with motion, positions and normals.
PixelTaps referenceTaps(
    const Frame& f, const Frame& prev, const afn::ReprojectSettings& s, int x, int y)
{
    PixelTaps t;
    const float px = static_cast<float>(x) + f.motion(x, y, 0);
    const float py = static_cast<float>(y) + f.motion(x, y, 1);
    if (!(std::fabs(px) < 1e7f) || !(std::fabs(py) < 1e7f))
        return t;
    // Footprint: max over the axes of the smaller distance to the two neighbours' positions.
    float fp = 0.0f;
    for (int axis = 0; axis < 2; ++axis) {
        float best = -1.0f;
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            const int nx = x + (axis == 0 ? sgn : 0), ny = y + (axis == 1 ? sgn : 0);
            if (nx < 0 || ny < 0 || nx >= W || ny >= H)
                continue;
            const float d = std::sqrt(dist2(f.position.at(x, y), f.position.at(nx, ny)));
            if (best < 0.0f || d < best)
                best = d;
        }
        fp = std::fmax(fp, std::fmax(best, 0.0f));
    }
    auto accept = [&](int tx, int ty) {
        if (tx < 0 || ty < 0 || tx >= W || ty >= H)
            return false;
        const float d2 = dist2(prev.position.at(tx, ty), f.position.at(x, y));
        const float lim = s.positionLimit * fp;
        if (!(d2 == 0.0f || d2 < lim * lim))
            return false;
        const float* n = f.normal.at(x, y);
        const float* np = prev.normal.at(tx, ty);
        const bool zero = (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f)
            || (np[0] == 0.0f && np[1] == 0.0f && np[2] == 0.0f);
        return !zero && dist2(n, np) < s.normalLimitSquared;
    };
    t.onScreen = 1;
    t.x0 = static_cast<int>(std::floor(px));
    t.y0 = static_cast<int>(std::floor(py));
    t.fx = px - std::floor(px);
    t.fy = py - std::floor(py);
    const float bw[4] = { (1.0f - t.fx) * (1.0f - t.fy), t.fx * (1.0f - t.fy), (1.0f - t.fx) * t.fy,
        t.fx * t.fy };
    float ws = 0.0f;
    for (int k = 0; k < 4; ++k)
        if (bw[k] > 0.0f && accept(t.x0 + (k & 1), t.y0 + (k >> 1))) {
            t.mask |= static_cast<std::uint16_t>(1u << k);
            t.w[k] = bw[k];
            ws += bw[k];
        }
    if (ws > 0.0f || !s.boxFallback)
        return t;
    const int cx = static_cast<int>(std::floor(px + 0.5f));
    const int cy = static_cast<int>(std::floor(py + 0.5f));
    std::uint16_t mask = 0;
    for (int k = 0; k < 9; ++k)
        if (accept(cx + k % 3 - 1, cy + k / 3 - 1))
            mask |= static_cast<std::uint16_t>(1u << k);
    if (mask) {
        t.box = 1;
        t.mask = mask;
        t.x0 = cx;
        t.y0 = cy;
    }
    return t;
}

void expectSameTaps(const PixelTaps& a, const PixelTaps& b, int x, int y)
{
    EXPECT_EQ(a.onScreen, b.onScreen) << x << "," << y;
    EXPECT_EQ(a.box, b.box) << x << "," << y;
    EXPECT_EQ(a.mask, b.mask) << x << "," << y;
    EXPECT_EQ(a.x0, b.x0) << x << "," << y;
    EXPECT_EQ(a.y0, b.y0) << x << "," << y;
    EXPECT_EQ(a.fx, b.fx) << x << "," << y;
    EXPECT_EQ(a.fy, b.fy) << x << "," << y;
    for (int k = 0; k < 4; ++k)
        EXPECT_EQ(a.w[k], b.w[k]) << x << "," << y << " tap " << k;
}

/// A surface with a bump and a crease; `seed` perturbs positions and normals of a few pixels
/// (disocclusions), `moving(y)` says which rows get motion (others get exactly zero).
template <typename Moving> Frame sceneFrame(std::uint32_t seed, Moving moving)
{
    methods_test::Lcg rng { seed };
    Frame f;
    f.width = W;
    f.height = H;
    f.color = Image(W, H, 3, 1.0f);
    f.position = makeImage(W, H, 3, [](int x, int y, int c) {
        return c == 0 ? 0.1f * x : c == 1 ? 0.1f * y : (x > W / 2 ? 0.05f * (x - W / 2) : 0.0f);
    });
    f.normal = makeImage(W, H, 3, [](int x, int, int c) {
        return x > W / 2 ? (c == 0 ? -0.7071f : c == 2 ? 0.7071f : 0.0f) : (c == 2 ? 1.0f : 0.0f);
    });
    f.motion = Image(W, H, 2, 0.0f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float u = rng.next(), v = rng.next(), r = rng.next();
            if (moving(y)) {
                f.motion(x, y, 0) = std::round(u * 8.0f) / 4.0f; // multiples of 1/4, some 0
                f.motion(x, y, 1) = std::round(v * 4.0f) / 4.0f;
            }
            if (r > 0.8f)
                f.position(x, y, 2) += 0.3f * r; // moved: rejected by the position test
            else if (r < -0.9f)
                f.normal(x, y, 0) = f.normal(x, y, 1) = f.normal(x, y, 2) = 0.0f;
        }
    return f;
}

TEST(ReprojectIdentity, TapsMatchALiteralEvaluationOfTheRule)
{
    for (bool box : { false, true }) {
        afn::ReprojectSettings s;
        s.boxFallback = box;
        const Frame prev = sceneFrame(7u, [](int) { return false; });
        // Rows 0-3 static (identity rows), the rest moving.
        const Frame cur = sceneFrame(11u, [](int y) { return y >= 4; });
        afn::Reprojector r;
        r.setSettings(s);
        r.storeGeometry(prev);
        r.compute(cur);
        int accepted = 0, rejected = 0, boxes = 0;
        for (int y = 0; y < H; ++y) {
            EXPECT_EQ(r.identityRow(y), y < 4) << y;
            for (int x = 0; x < W; ++x) {
                const PixelTaps want = referenceTaps(cur, prev, s, x, y);
                expectSameTaps(r.taps(x, y), want, x, y);
                accepted += want.mask != 0 && !want.box;
                rejected += want.mask == 0;
                boxes += want.box;
            }
        }
        // The scene exercises every outcome.
        EXPECT_GT(accepted, 0);
        EXPECT_GT(rejected, 0);
        if (box)
            EXPECT_GT(boxes, 0);
    }
}

TEST(ReprojectIdentity, StaticRowsGiveTheTapsOfTheGeneralPath)
{
    // Same frames, except that in `general` the last column moves, so that no row is an identity
    // row; every other pixel has zero motion in both.
    const Frame prev = sceneFrame(3u, [](int) { return false; });
    const Frame still = sceneFrame(5u, [](int) { return false; });
    Frame general = still;
    for (int y = 0; y < H; ++y)
        general.motion(W - 1, y, 0) = -0.5f;
    afn::Reprojector a, b;
    a.storeGeometry(prev);
    b.storeGeometry(prev);
    a.compute(still);
    b.compute(general);
    for (int y = 0; y < H; ++y) {
        EXPECT_TRUE(a.identityRow(y));
        EXPECT_FALSE(b.identityRow(y));
        for (int x = 0; x < W - 1; ++x)
            expectSameTaps(a.taps(x, y), b.taps(x, y), x, y);
    }
}

TEST(ReprojectIdentity, TaOfAStaticSequenceMatchesTheGeneralPath)
{
    // "ta" over 4 frames of a static camera; in the second run the last column moves, which
    // sends every row through the general path. The other pixels' outputs are bit-identical.
    auto run = [](bool moveLastColumn) {
        auto filter = afn::createFilter("ta");
        // The path equivalence of the accumulation (the moving column would change the history
        // trust of its blocks and their neighbours).
        filter->params().setNumber("antilag", 0.0, AFN_PARAM_FLOAT);
        std::vector<Image> outs;
        for (int k = 0; k < 4; ++k) {
            const Frame f = sceneFrame(100u + k, [](int) { return false; });
            methods_test::Buffers b;
            methods_test::Lcg rng { 200u + k };
            b.color = makeImage(W, H, 3, [&](int, int, int) { return 1.0f + rng.next(); });
            b.albedo = Image(W, H, 3, 0.5f);
            b.normal = f.normal;
            b.position = f.position;
            b.motion = f.motion;
            if (moveLastColumn)
                for (int y = 0; y < H; ++y)
                    b.motion(W - 1, y, 1) = 0.25f;
            methods_test::runFrame(*filter, b);
            outs.push_back(b.out);
        }
        return outs;
    };
    const std::vector<Image> still = run(false), general = run(true);
    int differing = 0;
    for (std::size_t k = 0; k < still.size(); ++k)
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                for (int c = 0; c < 3; ++c) {
                    if (x < W - 1)
                        EXPECT_EQ(still[k](x, y, c), general[k](x, y, c))
                            << k << " " << x << "," << y;
                    else
                        differing += still[k](x, y, c) != general[k](x, y, c);
                }
    EXPECT_GT(differing, 0); // the moving column really took another history
}

} // namespace
