// SPDX-License-Identifier: Apache-2.0
// svgf's `spread` (methods/svgf/denoiser.h step 3; kernels.h sparseShare) through createFilter on a
// first frame, where every pixel takes the 7x7 estimate:
//   - a few bright samples among black pixels on a flat plane (1 spp of a dim surface): with the
//     spread the frame keeps its mean and no pixel stays black; with the paper's estimate
//     (spread=off) most pixels stay black: the failure the spread is for;
//   - spread=auto is off from 4 spp (the shared "spp" parameter): the paper's estimate, bit for
//   bit;
//   - an image-like frame (a lighting gradient with mild noise; coefficients of variation below
//     1) gives the same bits with and without the spread.
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

namespace {

using afn::Image;
using methods_test::Buffers;
using methods_test::makeImage;
using methods_test::runFrame;

constexpr int W = 64, H = 64;

/// A flat plane facing the camera; colour from `value(x, y)` on every channel.
template <typename Value> Buffers flatPlane(Value&& value)
{
    Buffers b;
    b.normal = makeImage(W, H, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    b.position = makeImage(W, H, 3, [](int x, int y, int c) {
        return c == 0 ? x : c == 1 ? y : 0.0f;
    });
    b.color = makeImage(W, H, 3, [&](int x, int y, int) { return value(x, y); });
    return b;
}

/// 1 in 16 pixels (a fixed hash) holds 64, the others 0: a mean of 4, bright samples far above
/// the paper's absolute luminance sigma (4).
Buffers sparseSamples()
{
    return flatPlane([](int x, int y) {
        const std::uint32_t h = (static_cast<std::uint32_t>(x) * 73856093u)
            ^ (static_cast<std::uint32_t>(y) * 19349663u);
        return (h * 2654435761u >> 28) == 0 ? 64.0f : 0.0f;
    });
}

Image firstFrame(Buffers b, const char* spread, int spp = 0)
{
    auto f = afn::createFilter("svgf");
    f->params().setString("spread", spread);
    f->params().setNumber(AFN_PARAM_SPP, spp, AFN_PARAM_INT);
    runFrame(*f, b);
    return b.out;
}

struct Summary {
    double inputMean = 0.0, outputMean = 0.0, blackShare = 0.0;
};

/// Means over the frame less an 8-pixel border, and the share of its pixels below a quarter of the
/// input's mean ("black").
Summary summarise(const Buffers& in, const Image& out)
{
    Summary s;
    int n = 0;
    for (int y = 8; y < H - 8; ++y)
        for (int x = 8; x < W - 8; ++x, ++n) {
            s.inputMean += in.color(x, y, 0);
            s.outputMean += out(x, y, 0);
        }
    s.inputMean /= n;
    s.outputMean /= n;
    for (int y = 8; y < H - 8; ++y)
        for (int x = 8; x < W - 8; ++x)
            s.blackShare += out(x, y, 0) < 0.25 * s.inputMean ? 1.0 : 0.0;
    s.blackShare /= n;
    return s;
}

TEST(SvgfSparseSamples, SpreadKeepsTheMeanAndLeavesNoPixelBlack)
{
    const Buffers b = sparseSamples();
    const Summary on = summarise(b, firstFrame(b, "auto")); // spp unknown: spread
    const Summary off = summarise(b, firstFrame(b, "off"));
    std::printf(
        "input mean %.3f; spread: mean %.3f, black %.1f %%; the paper's estimate: mean %.3f, "
        "black %.1f %%\n",
        on.inputMean, on.outputMean, 100.0 * on.blackShare, off.outputMean, 100.0 * off.blackShare);
    ASSERT_NEAR(on.inputMean, 4.0, 1.0); // the hash's share is about 1/16
    EXPECT_NEAR(on.outputMean, on.inputMean, 0.1 * on.inputMean);
    EXPECT_LT(on.blackShare, 0.02);
    EXPECT_GT(off.blackShare, 0.5) << "the paper's estimate keeps most pixels black";
}

TEST(SvgfSparseSamples, AutoIsOffFromFourSamplesPerPixel)
{
    const Buffers b = sparseSamples();
    EXPECT_TRUE(methods_test::bitEqual(firstFrame(b, "auto", 4), firstFrame(b, "off")));
    EXPECT_TRUE(methods_test::bitEqual(firstFrame(b, "auto", 3), firstFrame(b, "on")));
    EXPECT_FALSE(methods_test::bitEqual(firstFrame(b, "on"), firstFrame(b, "off")));
}

TEST(SvgfSparseSamples, AnImageLikeFrameKeepsThePapersEstimate)
{
    methods_test::Lcg rng { 99u };
    const Buffers b = flatPlane(
        [&](int x, int y) { return (0.2f + 0.02f * x + 0.01f * y) * (1.0f + 0.1f * rng.next()); });
    EXPECT_TRUE(methods_test::bitEqual(firstFrame(b, "on"), firstFrame(b, "off")));
}

} // namespace
