// SPDX-License-Identifier: Apache-2.0
// The post-filter's per-pixel luminance scale (methods/afn/post_filter_noise.h): exact small cases
// (no irradiance: the constant of before; a flat irradiance: the low end; a checkerboard: the
// formula; history divides the variance, up to the accumulation's limit; non-finite values stay
// in range; rows from any first row give the whole frame's bits) and, through the post-filter, a
// noisier irradiance smoothing the same radiance more.
#include "methods/afn/post_filter.h"
#include "methods/afn/post_filter_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using afn::Image;
using afn::afnet::kPostFilterNoiseClamp;
using afn::afnet::kPostFilterNoiseReference;
using afn::afnet::kPostFilterSigmaLuminance;
using afn::afnet::PostFilterNoiseInputs;

constexpr int kW = 20, kH = 12;
constexpr float kBase = 0.5f * kPostFilterSigmaLuminance;

/// The scale of the rows from `first` to the last (those above `first` left 0).
std::vector<float> scaleOf(const PostFilterNoiseInputs& in, int first = 0)
{
    std::vector<float> storage(afn::afnet::PostFilterNoiseRows::storageFloats(kW)), scale(kW * kH);
    afn::afnet::PostFilterNoiseRows rows(in, kW, kH, kPostFilterSigmaLuminance, storage.data());
    for (int y = first; y < kH; ++y)
        rows.row(y, scale.data() + y * kW);
    return scale;
}

/// Grey irradiance: a where (x + y) is even, b where it is odd.
Image checkerboard(float a, float b)
{
    Image im(kW, kH, 3);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c)
                im.at(x, y)[c] = (x + y) % 2 == 0 ? a : b;
    return im;
}

/// The scale at an interior pixel whose 5x5 box holds `na` values a and `nb` values b, with
/// `samples` behind it (the formula of post_filter_noise.h in double precision).
double expectedScale(double a, double b, int na, int nb, double samples)
{
    const double n = na + nb, mean = (na * a + nb * b) / n;
    const double variance = (na * a * a + nb * b * b) / n - mean * mean;
    const double noise = std::sqrt(variance / samples) / (mean + 1e-3);
    const double m = std::clamp(noise / kPostFilterNoiseReference, 1.0 / kPostFilterNoiseClamp,
        double(kPostFilterNoiseClamp));
    return kBase * m;
}

TEST(AfnPostFilterNoise, WithoutIrradianceEveryPixelGetsTheConstantOfBefore)
{
    const Image small(kW / 2, kH, 3, 1.0f);
    for (const PostFilterNoiseInputs& in :
        { PostFilterNoiseInputs {}, PostFilterNoiseInputs { &small, nullptr, 9.0f } }) {
        const std::vector<float> s = scaleOf(in);
        ASSERT_EQ(s.size(), std::size_t(kW) * kH);
        for (float v : s)
            ASSERT_EQ(v, kBase);
    }
}

TEST(AfnPostFilterNoise, AFlatIrradianceGetsTheLowEnd)
{
    const Image flat(kW, kH, 3, 0.7f);
    for (float v : scaleOf({ &flat, nullptr, 9.0f }))
        ASSERT_FLOAT_EQ(v, kBase / kPostFilterNoiseClamp);
}

TEST(AfnPostFilterNoise, ACheckerboardGivesTheFormulaAndHistoryDividesTheVariance)
{
    // At (6, 6) the 5x5 box holds 13 even and 12 odd pixels. 0.6 / 0.2: relative noise about 0.5
    // per sample (the scale inside the clamp range for 1, 2 and 4 samples, at the low end for 9).
    const Image irradiance = checkerboard(0.6f, 0.2f);
    Image history(kW, kH, 1, 1.0f);
    const std::size_t p = 6 * kW + 6;
    for (const float samples : { 1.0f, 2.0f, 4.0f, 9.0f, 30.0f }) {
        for (std::size_t i = 0; i < history.size(); ++i)
            history.data()[i] = samples;
        const std::vector<float> s = scaleOf({ &irradiance, &history, 9.0f });
        const double expected = expectedScale(0.6, 0.2, 13, 12, std::min(samples, 9.0f));
        EXPECT_NEAR(s[p], expected, 1e-5 * expected) << samples;
    }
    // Without a history length: one sample; a history shorter than 1 counts as 1.
    for (std::size_t i = 0; i < history.size(); ++i)
        history.data()[i] = 0.0f;
    EXPECT_NEAR(scaleOf({ &irradiance, nullptr, 9.0f })[p], expectedScale(0.6, 0.2, 13, 12, 1.0),
        1e-5 * kBase);
    EXPECT_NEAR(scaleOf({ &irradiance, &history, 9.0f })[p], expectedScale(0.6, 0.2, 13, 12, 1.0),
        1e-5 * kBase);
}

TEST(AfnPostFilterNoise, ANoisyDarkRegionGetsTheHighEnd)
{
    // Relative noise about 1 per sample: above the reference wherever the box is the full 5x5 (at
    // the corners the clamped taps repeat the border and change the mix).
    const Image irradiance = checkerboard(0.0f, 0.05f);
    const std::vector<float> s = scaleOf({ &irradiance, nullptr, 9.0f });
    for (int y = 2; y < kH - 2; ++y)
        for (int x = 2; x < kW - 2; ++x)
            ASSERT_GT(s[y * kW + x], kBase) << x << "," << y;
    EXPECT_NEAR(s[6 * kW + 6], expectedScale(0.0, 0.05, 13, 12, 1.0), 1e-5 * kBase);
    // One firefly in a black 5x5 box: relative noise sqrt(24) per sample, above the clamp.
    Image firefly(kW, kH, 3, 0.0f);
    for (int c = 0; c < 3; ++c)
        firefly.at(6, 6)[c] = 1000.0f;
    EXPECT_EQ(scaleOf({ &firefly, nullptr, 9.0f })[6 * kW + 6], kBase * kPostFilterNoiseClamp);
    EXPECT_EQ(scaleOf({ &firefly, nullptr, 9.0f })[0], kBase / kPostFilterNoiseClamp);
}

TEST(AfnPostFilterNoise, NonFiniteInputsStayInRange)
{
    Image irradiance = checkerboard(0.5f, 0.3f);
    Image history(kW, kH, 1, 4.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    irradiance.at(3, 3)[0] = nan;
    irradiance.at(10, 5)[1] = inf;
    irradiance.at(15, 8)[2] = -inf;
    irradiance.at(1, 10)[0] = 3e38f; // its square overflows: inf - inf in the variance
    irradiance.at(1, 10)[1] = 3e38f;
    history.at(4, 4)[0] = nan;
    history.at(12, 2)[0] = inf;
    history.at(6, 9)[0] = -5.0f;
    for (float v : scaleOf({ &irradiance, &history, 9.0f })) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, kBase / kPostFilterNoiseClamp);
        ASSERT_LE(v, kBase * kPostFilterNoiseClamp);
    }
}

// A band of the post-filter's rows asks for the scale from its own first row on: every row from
// there has the bits of the whole frame's run, at the top, in the middle and near the bottom.
TEST(AfnPostFilterNoise, RowsFromAnyFirstRowGiveTheWholeFramesBits)
{
    Image irradiance(kW, kH, 3), history(kW, kH, 1);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (std::size_t i = 0; i < irradiance.size(); ++i)
        irradiance.data()[i] = u(rng);
    for (std::size_t i = 0; i < history.size(); ++i)
        history.data()[i] = 1.0f + 10.0f * u(rng);
    const PostFilterNoiseInputs in { &irradiance, &history, 9.0f };
    const std::vector<float> whole = scaleOf(in);
    for (int first : { 1, 2, 3, kH / 2, kH - 3, kH - 1 }) {
        const std::vector<float> part = scaleOf(in, first);
        for (int i = first * kW; i < kW * kH; ++i)
            ASSERT_EQ(part[i], whole[i]) << "first row " << first << ", value " << i;
    }
}

TEST(AfnPostFilterNoise, ANoisierIrradianceSmoothsTheSameRadianceMore)
{
    // The same noisy radiance on a flat surface, filtered with a flat irradiance (low end: least
    // smoothing) and with a noisy one (high end): the second leaves less noise.
    Image radiance(kW, kH, 3, 0.5f);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.1f, 0.1f);
    for (std::size_t i = 0; i < radiance.size(); ++i)
        radiance.data()[i] += u(rng);
    const Image flat(kW, kH, 3, 0.5f), noisy = checkerboard(0.0f, 0.1f);
    double spread[2];
    for (int k = 0; k < 2; ++k) {
        afn::afnet::PostFilterGuides g;
        g.noise.irradiance = k == 0 ? &flat : &noisy;
        afn::afnet::PostFilterWorkspace ws;
        Image out;
        afn::afnet::edgeAwarePostFilter(radiance, g, ws, out);
        double s = 0.0;
        for (std::size_t i = 0; i < out.size(); ++i)
            s += (out.data()[i] - 0.5) * (out.data()[i] - 0.5);
        spread[k] = std::sqrt(s / out.size());
    }
    EXPECT_LT(spread[1], 0.8 * spread[0]);
}

} // namespace
