// SPDX-License-Identifier: Apache-2.0
// BMFR's detail restoration (methods/bmfr/detail.cpp): at 16 spp, fine lighting detail the block
// fit cannot express comes back (the published fit flattens it below the noisy input); with heavy
// noise the fit is kept; detail=auto follows the spp parameter, and below 4 spp is bit-identical to
// detail=off.
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

using afn::Image;
using methods_test::Buffers;
using methods_test::makeImage;
using methods_test::runFrame;

constexpr int W = 64, H = 64;

/// Fine stripes of lighting (period 3 pixels) on a flat, static surface.
float truth(int x, int y)
{
    return 0.5f * (1.0f + 0.6f * ((x + y) % 3 == 0 ? 1.0f : -0.5f));
}

Buffers scene(int frame, float noise)
{
    Buffers b;
    b.albedo = Image(W, H, 3, 0.5f);
    b.normal = makeImage(W, H, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    b.depth = Image(W, H, 1, 2.0f);
    b.motion = Image(W, H, 2, 0.0f);
    methods_test::Lcg rng { 7919u * static_cast<std::uint32_t>(frame) + 3u };
    b.color = makeImage(W, H, 3,
        [&](int x, int y, int) { return truth(x, y) * std::max(0.0f, 1.0f + noise * rng.next()); });
    return b;
}

double errorAfter(const std::string& detail, int spp, float noise, Image* last = nullptr)
{
    auto f = afn::createFilter("bmfr");
    f->params().setString("detail", detail);
    f->params().setNumber("spp", spp, AFN_PARAM_INT);
    Buffers b;
    for (int k = 0; k < 12; ++k) {
        b = scene(k, noise);
        runFrame(*f, b);
    }
    if (last)
        *last = b.out;
    const Image clean = makeImage(W, H, 3, [](int x, int y, int) { return truth(x, y); });
    return methods_test::rmse(b.out, clean);
}

TEST(BmfrDetail, FineDetailComesBackAtSixteenSpp)
{
    const double published = errorAfter("off", 16, 0.1f);
    const double kept = errorAfter("auto", 16, 0.1f);
    const Image noisy = scene(11, 0.1f).color;
    const Image clean = makeImage(W, H, 3, [](int x, int y, int) { return truth(x, y); });
    const double input = methods_test::rmse(noisy, clean);
    EXPECT_GT(published, input) << "the fit alone flattens the stripes below the noisy input";
    // Most of the detail returns; what is left is the first frame's flattened fit, which has no
    // history to measure the noise against and fades through the second accumulation and TAA.
    EXPECT_LT(kept, 0.25 * published) << "published " << published << ", input " << input;
    EXPECT_LT(kept, 1.5 * input) << "published " << published << ", input " << input;
}

TEST(BmfrDetail, HeavyNoiseKeepsTheFit)
{
    // 1-spp-like noise: restoring the residual would restore noise; the fit stays near as good.
    const double published = errorAfter("off", 16, 1.0f);
    const double kept = errorAfter("on", 16, 1.0f);
    EXPECT_LT(kept, 1.1 * published);
}

TEST(BmfrDetail, AutoIsOffBelowFourSpp)
{
    Image a, b;
    errorAfter("auto", 1, 0.1f, &a);
    errorAfter("off", 1, 0.1f, &b);
    EXPECT_TRUE(methods_test::bitEqual(a, b));
    errorAfter("auto", 0, 0.1f, &a); // unknown sample count: as 1 spp
    EXPECT_TRUE(methods_test::bitEqual(a, b));
}

} // namespace
