// SPDX-License-Identifier: Apache-2.0
// The highlight bypass (stages/highlight_bypass.h): the limit is the factor times the power of two
// above the 99th percentile of the sampled pixels' largest channel; the split keeps exactly the
// excess over the limit, per channel, of the pixels above it; an image with nothing above the
// limit is used as it is (no copy), one with a value above it is clamped per channel.
#include "stages/highlight_bypass.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using afn::HighlightBypass;
using afn::highlightLimit;
using afn::Image;

/// 40 x 40: the 100 sampled pixels (every 4th row and column) at 0.75 except one at 1000, so
/// the 99th percentile (the 99th of 100) is 0.75, in [0.5, 1): upper edge 1.
Image sampledImage()
{
    Image img(40, 40, 3, 0.75f);
    for (int k = 0; k < 3; ++k)
        img(8, 12, k) = k == 1 ? 1000.0f : 0.5f;
    img(1, 1, 0) = 500.0f; // not a sampled pixel: no effect on the limit
    return img;
}

} // namespace

TEST(HighlightBypass, LimitIsTheFactorTimesThePercentilesPowerOfTwo)
{
    const Image img = sampledImage();
    EXPECT_EQ(highlightLimit(img, 8.0f), 8.0f);
    EXPECT_EQ(highlightLimit(img, 3.0f), 3.0f);
    // Two sampled pixels above: the 99th value is now 1000, in [512, 1024).
    Image two = img;
    two(0, 0, 2) = 1000.0f;
    EXPECT_EQ(highlightLimit(two, 8.0f), 8.0f * 1024.0f);
    // A black frame: the smallest bin, 2^-64.
    EXPECT_EQ(highlightLimit(Image(40, 40, 3, 0.0f), 8.0f), 8.0f * std::ldexp(1.0f, -64));
    // Off, or nothing to measure.
    EXPECT_TRUE(std::isinf(highlightLimit(img, 0.0f)));
    EXPECT_TRUE(std::isinf(highlightLimit(Image(), 8.0f)));
}

TEST(HighlightBypass, SplitKeepsTheExcessAndClampsPerChannel)
{
    const Image img = sampledImage();
    HighlightBypass b;
    b.split(img, 8.0f);
    ASSERT_EQ(b.pixels(), 2);
    const Image& c = b.clamped(img, 0);
    ASSERT_NE(&c, &img);
    EXPECT_EQ(c(1, 1, 0), 8.0f);
    EXPECT_EQ(c(8, 12, 1), 8.0f);
    EXPECT_EQ(c(8, 12, 0), 0.5f); // channels at or below the limit unchanged
    EXPECT_EQ(c(3, 3, 2), 0.75f);
    // clamped + excess (factor 1) = the image, bit for bit.
    Image sum = c;
    b.addExcess(sum, [](int, int, int) { return 1.0f; });
    for (std::size_t i = 0; i < img.size(); ++i)
        ASSERT_EQ(sum.data()[i], img.data()[i]) << i;
    // The factor scales each pixel's excess (the remodulation's albedo).
    Image zero(40, 40, 3, 0.0f);
    b.addExcess(
        zero, [](int x, int, int k) { return x == 8 ? 0.5f * static_cast<float>(k + 1) : 2.0f; });
    EXPECT_EQ(zero(8, 12, 1), (1000.0f - 8.0f) * 1.0f);
    EXPECT_EQ(zero(8, 12, 0), 0.0f);
    EXPECT_EQ(zero(1, 1, 0), (500.0f - 8.0f) * 2.0f);
}

TEST(HighlightBypass, NothingAboveTheLimitIsUsedAsItIs)
{
    const Image img(40, 40, 3, 0.75f);
    HighlightBypass b;
    b.split(img, highlightLimit(img, 8.0f));
    EXPECT_EQ(b.pixels(), 0);
    EXPECT_EQ(&b.clamped(img, 1), &img);
    // Off: nothing split, nothing clamped, whatever the values.
    const Image bright = sampledImage();
    b.split(bright, highlightLimit(bright, 0.0f));
    EXPECT_EQ(b.pixels(), 0);
    EXPECT_EQ(&b.clamped(bright, 0), &bright);
}
