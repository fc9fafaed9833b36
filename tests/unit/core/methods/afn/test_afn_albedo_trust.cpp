// SPDX-License-Identifier: Apache-2.0
// The shipped afn models where the renderer's albedo is noise: a static scene whose albedo is
// clean except inside a disc (a "glass" object: there the albedo buffer is a new per-pixel
// lottery every frame while the colour is smooth). afn with every input must do no worse inside
// the disc than its colour-only model, and no worse outside it either (the albedo helps there).
// The learned albedo trust (methods/afn/albedo_trust.h) and the aux prefilter
// (stages/aux_prefilter.h) are what let it.
#include "afn_test_util.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using afn::Image;
using methods_test::Buffers;
using methods_test::makeImage;

constexpr int W = 96, H = 96, kFrames = 6;
constexpr float kRadius = 26.0f;

bool inDisc(int x, int y)
{
    const float dx = x + 0.5f - W / 2.0f, dy = y + 0.5f - H / 2.0f;
    return dx * dx + dy * dy < kRadius * kRadius;
}

/// The clean colour: a checker of albedos under a soft light outside the disc, a smooth
/// refracted-looking gradient inside.
Image truth()
{
    return makeImage(W, H, 3, [](int x, int y, int c) {
        if (inDisc(x, y))
            return 0.35f + 0.25f * std::sin(0.15f * x + 0.5f * c) * std::cos(0.1f * y);
        const float albedo = ((x / 8 + y / 8) % 2 ? 0.7f : 0.25f) - 0.05f * c;
        return albedo * (0.8f + 0.4f * y / H);
    });
}

/// Frame k: the colour with +-90 % noise, the albedo clean outside the disc and random inside.
Buffers frame(const Image& clean, int k, bool aux)
{
    Buffers b;
    methods_test::Lcg rng { 7919u * static_cast<std::uint32_t>(k) + 3u };
    b.color = makeImage(
        W, H, 3, [&](int x, int y, int c) { return clean(x, y, c) * (1.0f + 0.9f * rng.next()); });
    if (!aux)
        return b;
    b.albedo = makeImage(W, H, 3, [&](int x, int y, int c) {
        if (inDisc(x, y))
            return 0.525f + 0.475f * rng.next(); // [0.05, 1)
        return ((x / 8 + y / 8) % 2 ? 0.7f : 0.25f) - 0.05f * c;
    });
    b.normal = makeImage(W, H, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    b.depth = Image(W, H, 1, 2.0f);
    b.motion = Image(W, H, 2, 0.0f);
    return b;
}

/// RMSE of the last frame's output against the clean colour, inside and outside the disc;
/// `auxMode` is the aux prefilter's mode (stages/aux_prefilter.h).
void runSequence(bool aux, double* inside, double* outside, const char* auxMode = "auto")
{
    auto f = afn::createFilter("afn");
    f->params().setString("aux", auxMode);
    const Image clean = truth();
    Buffers b;
    for (int k = 0; k < kFrames; ++k) {
        Buffers next = frame(clean, k, aux);
        next.out = b.out;
        b = std::move(next);
        methods_test::runFrame(*f, b);
    }
    double sum[2] = {}, n[2] = {};
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = b.out(x, y, c) - clean(x, y, c);
                sum[inDisc(x, y)] += d * d;
                n[inDisc(x, y)] += 1.0;
            }
    *outside = std::sqrt(sum[0] / n[0]);
    *inside = std::sqrt(sum[1] / n[1]);
}

} // namespace

TEST(AfnAlbedoTrust, NoisyAlbedoInADiscIsNoWorseThanTheColourOnlyModel)
{
    if (!afn::findFilterType("afn")->ready)
        GTEST_SKIP() << "no embedded afn weights in this build";
    double allIn = 0, allOut = 0, colourIn = 0, colourOut = 0;
    runSequence(true, &allIn, &allOut);
    runSequence(false, &colourIn, &colourOut);
    std::printf("inside the disc: every input %.4f, colour only %.4f; outside %.4f, %.4f\n", allIn,
        colourIn, allOut, colourOut);
    EXPECT_LE(allIn, 1.02 * colourIn);
    EXPECT_LE(allOut, 1.02 * colourOut);
}

TEST(AfnAlbedoTrust, TheDiscIsAFailureCaseWhenTheNoisyAlbedoIsTakenAsClean)
{
    // The test above can fail: with aux=clean (the albedo taken as given, no prefilter) the
    // shipped full-input model is far worse than the colour-only one inside the disc.
    if (!afn::findFilterType("afn")->ready)
        GTEST_SKIP() << "no embedded afn weights in this build";
    double in = 0, out = 0, colourIn = 0, colourOut = 0;
    runSequence(true, &in, &out, "clean");
    runSequence(false, &colourIn, &colourOut);
    std::printf("aux=clean inside the disc %.4f (colour only %.4f)\n", in, colourIn);
    EXPECT_GT(in, 1.5 * colourIn);
}
