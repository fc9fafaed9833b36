// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (methods/afn/post_filter.h): exact small cases (a constant image
// stays constant; albedo and depth edges are kept; noise on a flat surface is smoothed;
// non-finite guides do not spread; absent guides leave their terms out; each result is a convex
// combination of the input, negative radiance included; a workspace reused across frames and
// sizes gives what a fresh one gives; the formula in double on every run kind and in every band
// of rows, the same bits whatever the thread count) and, in the afn filter, postFilter=auto
// following the sample count of the model that runs.
#include "afn_synthetic_sequence.h"
#include "afn_test_util.h"
#include "filter/registry.h"
#include "methods/afn/post_filter.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using afn::Image;
using afn::afnet::edgeAwarePostFilter;
using afn::afnet::PostFilterGuides;
using afn::afnet::PostFilterWorkspace;

constexpr int kW = 40, kH = 24;

Image filled(int channels, float v)
{
    return Image(kW, kH, channels, v);
}

/// Flat guides: one albedo, one normal facing the camera, one depth.
struct FlatGuides {
    Image albedo = filled(3, 0.5f);
    Image normal = filled(3, 0.0f);
    Image depth = filled(1, 2.0f);
    FlatGuides()
    {
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                normal.at(x, y)[2] = 1.0f;
    }
    PostFilterGuides guides() const { return { &albedo, &normal, &depth }; }
};

/// The post-filter with a fresh workspace of its own.
Image filter(const Image& radiance, const PostFilterGuides& g)
{
    PostFilterWorkspace workspace;
    Image out;
    edgeAwarePostFilter(radiance, g, workspace, out);
    return out;
}

/// 0.5 plus uniform noise in [-0.05, 0.05) per value, from `seed`.
Image noisyFlat(unsigned seed)
{
    Image radiance = filled(3, 0.5f);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.05f, 0.05f);
    for (std::size_t i = 0; i < radiance.size(); ++i)
        radiance.data()[i] += u(rng);
    return radiance;
}

double stddev(const Image& im, int c)
{
    double s = 0.0, s2 = 0.0;
    const int n = im.width() * im.height();
    for (int y = 0; y < im.height(); ++y)
        for (int x = 0; x < im.width(); ++x) {
            const double v = im.at(x, y)[c];
            s += v;
            s2 += v * v;
        }
    return std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)));
}

} // namespace

TEST(AfnPostFilter, ConstantImageStaysConstant)
{
    FlatGuides g;
    std::mt19937 rng(3); // guides with edges everywhere must not move a constant
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (std::size_t i = 0; i < g.albedo.size(); ++i)
        g.albedo.data()[i] = u(rng);
    for (std::size_t i = 0; i < g.depth.size(); ++i)
        g.depth.data()[i] = 1.0f + 10.0f * u(rng);
    const Image out = filter(filled(3, 0.37f), g.guides());
    ASSERT_EQ(out.width(), kW);
    ASSERT_EQ(out.height(), kH);
    ASSERT_EQ(out.channels(), 3);
    for (std::size_t i = 0; i < out.size(); ++i)
        ASSERT_NEAR(out.data()[i], 0.37f, 1e-6f) << i;
}

TEST(AfnPostFilter, AlbedoEdgeIsKept)
{
    FlatGuides g;
    Image radiance = filled(3, 0.1f);
    for (int y = 0; y < kH; ++y)
        for (int x = kW / 2; x < kW; ++x)
            for (int c = 0; c < 3; ++c) {
                g.albedo.at(x, y)[c] = 0.9f;
                radiance.at(x, y)[c] = 0.9f;
            }
    const Image out = filter(radiance, g.guides());
    for (int y = 0; y < kH; ++y) {
        EXPECT_NEAR(out.at(kW / 2 - 1, y)[0], 0.1f, 1e-3f) << y;
        EXPECT_NEAR(out.at(kW / 2, y)[0], 0.9f, 1e-3f) << y;
    }
}

TEST(AfnPostFilter, DepthEdgeIsKeptWhereAlbedoAndNormalAgree)
{
    FlatGuides g;
    Image radiance = filled(3, 0.2f);
    for (int y = kH / 2; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            g.depth.at(x, y)[0] = 6.0f; // a surface three times as far, same albedo and normal
            for (int c = 0; c < 3; ++c)
                radiance.at(x, y)[c] = 0.3f; // a small step: luminance alone would blur it
        }
    const Image out = filter(radiance, g.guides());
    for (int x = 0; x < kW; ++x) {
        EXPECT_NEAR(out.at(x, kH / 2 - 1)[1], 0.2f, 1e-3f) << x;
        EXPECT_NEAR(out.at(x, kH / 2)[1], 0.3f, 1e-3f) << x;
    }
}

TEST(AfnPostFilter, SmoothsNoiseOnAFlatSurface)
{
    FlatGuides g;
    const Image radiance = noisyFlat(7);
    const Image out = filter(radiance, g.guides());
    for (int c = 0; c < 3; ++c)
        EXPECT_LT(stddev(out, c), 0.3 * stddev(radiance, c)) << c;
}

TEST(AfnPostFilter, NonFiniteGuidesDoNotSpread)
{
    FlatGuides g;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    g.albedo.at(5, 5)[1] = nan;
    g.normal.at(9, 9)[0] = inf;
    g.normal.at(10, 9)[2] = nan;
    g.depth.at(20, 12)[0] = inf; // a background pixel
    g.depth.at(21, 12)[0] = nan;
    Image radiance = filled(3, 0.25f);
    radiance.at(30, 20)[0] = 1.0f;
    const Image out = filter(radiance, g.guides());
    for (std::size_t i = 0; i < out.size(); ++i)
        ASSERT_TRUE(std::isfinite(out.data()[i])) << i;
    EXPECT_NEAR(out.at(5, 5)[0], 0.25f, 1e-6f);
}

TEST(AfnPostFilter, AbsentOrMismatchedGuidesAreLeftOut)
{
    FlatGuides g;
    const Image radiance = noisyFlat(11);
    const Image small(kW / 2, kH, 3, 0.5f), none;
    // With flat guides their terms are all 0: the same as no guides, and as wrongly sized ones.
    const Image withFlat = filter(radiance, g.guides());
    const Image without = filter(radiance, PostFilterGuides {});
    const Image mismatched = filter(radiance, PostFilterGuides { &small, &none, &small });
    for (std::size_t i = 0; i < radiance.size(); ++i) {
        ASSERT_NEAR(withFlat.data()[i], without.data()[i], 1e-5f) << i;
        ASSERT_EQ(without.data()[i], mismatched.data()[i]) << i;
    }
}

TEST(AfnPostFilter, EmptyImage)
{
    PostFilterWorkspace workspace;
    Image out(3, 3, 3);
    edgeAwarePostFilter(Image(0, 0, 3), PostFilterGuides {}, workspace, out);
    EXPECT_EQ(out.size(), 0u);
}

TEST(AfnPostFilter, EachResultIsAConvexCombinationOfTheInputNegativeRadianceIncluded)
{
    // Radiance in [-50, 50): the weights stay non-negative and normalised where the luminance sum
    // of a pixel and its tap is negative (dl then takes it as 0).
    FlatGuides g;
    Image radiance = filled(3, 0.0f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-50.0f, 50.0f);
    for (std::size_t i = 0; i < radiance.size(); ++i)
        radiance.data()[i] = u(rng);
    float lo[3] = { 1e30f, 1e30f, 1e30f }, hi[3] = { -1e30f, -1e30f, -1e30f };
    for (std::size_t i = 0; i < radiance.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], radiance.data()[i]);
        hi[i % 3] = std::max(hi[i % 3], radiance.data()[i]);
    }
    const Image out = filter(radiance, g.guides());
    ASSERT_EQ(out.size(), radiance.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        ASSERT_TRUE(std::isfinite(out.data()[i])) << i;
        ASSERT_GE(out.data()[i], lo[i % 3] - 1e-3f) << i;
        ASSERT_LE(out.data()[i], hi[i % 3] + 1e-3f) << i;
    }
}

TEST(AfnPostFilter, AReusedWorkspaceGivesWhatAFreshOneGives)
{
    // Frames of two sizes through one workspace (as afn keeps it): each result is bit for bit
    // the one-call result, so nothing of an earlier frame's planes leaks into a later one.
    FlatGuides g;
    g.depth.at(5, 5)[0] = std::numeric_limits<float>::infinity();
    const Image a = noisyFlat(1), b = noisyFlat(2);
    const Image small(kW / 2, kH / 2, 3, 0.25f);
    PostFilterWorkspace ws;
    Image out;
    for (const Image* radiance : { &a, &small, &b }) {
        const bool full = radiance->width() == kW;
        const PostFilterGuides guides = full ? g.guides() : PostFilterGuides {};
        edgeAwarePostFilter(*radiance, guides, ws, out);
        const Image fresh = filter(*radiance, guides);
        ASSERT_EQ(out.size(), fresh.size());
        for (std::size_t i = 0; i < out.size(); ++i)
            ASSERT_EQ(out.data()[i], fresh.data()[i]) << i;
    }
}

TEST(AfnPostFilter, AutoFollowsTheSampleCountOfTheModel)
{
#ifndef AFN_HAS_EMBEDDED_WEIGHTS
    GTEST_SKIP() << "built without the shipped weights";
#else
    for (const int spp : { 1, 16 }) {
        std::unique_ptr<afn::Filter> f[3];
        const char* modes[3] = { "auto", "on", "off" };
        Image out[3];
        for (int m = 0; m < 3; ++m) {
            f[m] = afn::createFilter("afn");
            f[m]->params().setString("postFilter", modes[m]);
            f[m]->params().setNumber("spp", spp, AFN_PARAM_INT);
            out[m] = Image(kW, kH, 3);
        }
        const afntest::SyntheticSequence seq(kW, kH, 7);
        for (int k = 0; k < 3; ++k)
            for (int m = 0; m < 3; ++m) {
                afntest::SequenceFrame fr = seq.frame(k, {});
                afntest::runFrame(*f[m], fr, out[m]);
            }
        const Image& expected = spp == 1 ? out[1] : out[2];
        EXPECT_TRUE(std::equal(out[0].data(), out[0].data() + out[0].size(), expected.data()))
            << spp << " spp";
        EXPECT_FALSE(std::equal(out[1].data(), out[1].data() + out[1].size(), out[2].data()))
            << spp << " spp";
    }
#endif
}

namespace {

/// The formula of post_filter.h, in double, half-pass by half-pass (taps clamped to the border).
std::vector<double> referencePostFilter(const Image& radiance, const Image& albedo,
    const Image& normal, const Image& depth, float sigma)
{
    const int w = radiance.width(), h = radiance.height();
    const double spline[5] = { 1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16 };
    std::vector<double> cur(radiance.data(), radiance.data() + radiance.size());
    auto unit = [&](int x, int y, double* n) {
        const float* m = normal.at(x, y);
        const double len2 = double(m[0]) * m[0] + double(m[1]) * m[1] + double(m[2]) * m[2];
        if (!(len2 > 0.5))
            return false;
        for (int c = 0; c < 3; ++c)
            n[c] = m[c] / std::sqrt(len2);
        return true;
    };
    for (int half = 0; half < 2 * afn::afnet::kPostFilterIterations; ++half) {
        const int step = 1 << (half / 2);
        const bool horizontal = half % 2 == 0;
        std::vector<double> next(cur.size());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double* cp = &cur[(std::size_t(y) * w + x) * 3];
                const double lp = 0.2126 * cp[0] + 0.7152 * cp[1] + 0.0722 * cp[2];
                double np[3];
                const bool vp = unit(x, y, np);
                const double zp = depth(x, y, 0);
                double acc[4] = {};
                for (int j = -2; j <= 2; ++j) {
                    const int qx = std::clamp(x + (horizontal ? j * step : 0), 0, w - 1);
                    const int qy = std::clamp(y + (horizontal ? 0 : j * step), 0, h - 1);
                    const double* cq = &cur[(std::size_t(qy) * w + qx) * 3];
                    const double lq = 0.2126 * cq[0] + 0.7152 * cq[1] + 0.0722 * cq[2];
                    const double ring = std::max(std::abs(j), 1);
                    double e = std::fabs(lp - lq) / (sigma * std::max(lp + lq, 0.0) + 1e-3);
                    for (int c = 0; c < 3; ++c)
                        e += std::fabs(double(albedo(x, y, c)) - albedo(qx, qy, c)) / 0.1;
                    e += std::fabs(zp - depth(qx, qy, 0))
                        / (0.02 * step * ring * std::max(zp, 1e-3) + 1e-6);
                    double nq[3];
                    double wn = 1.0;
                    if (vp && unit(qx, qy, nq))
                        wn = std::pow(
                            std::max(0.0, np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2]), 64);
                    const double wt = spline[j + 2] * wn * std::exp(-e);
                    for (int c = 0; c < 3; ++c)
                        acc[c] += wt * cq[c];
                    acc[3] += wt;
                }
                for (int c = 0; c < 3; ++c)
                    next[(std::size_t(y) * w + x) * 3 + c] = acc[c] / acc[3];
            }
        cur.swap(next);
    }
    return cur;
}

/// Random radiance and guides (some normals invalid, depth and albedo edges everywhere).
struct RandomFrame {
    Image radiance, albedo, normal, depth;
    RandomFrame(int w, int h, unsigned seed)
        : radiance(w, h, 3)
        , albedo(w, h, 3)
        , normal(w, h, 3)
        , depth(w, h, 1)
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                for (int c = 0; c < 3; ++c) {
                    radiance(x, y, c) = u(rng) * 2.0f;
                    albedo(x, y, c) = 0.4f + 0.1f * u(rng); // small steps: taps keep some weight
                    normal(x, y, c) = c == 2 ? 1.0f : 0.3f * (u(rng) - 0.5f);
                }
                if (u(rng) < 0.1f)
                    normal(x, y, 0) = normal(x, y, 1) = normal(x, y, 2) = 0.0f; // no normal here
                depth(x, y, 0) = 2.0f + 0.02f * u(rng) + (x > w / 2 ? 1.0f : 0.0f);
            }
    }
    PostFilterGuides guides() const { return { &albedo, &normal, &depth }; }
};

/// The post-filter run by `threads` threads (the frame is split into one band per thread).
Image filterWithThreads(const RandomFrame& f, int threads)
{
    tbb::task_arena arena(threads);
    Image out;
    arena.execute([&] {
        PostFilterWorkspace workspace;
        edgeAwarePostFilter(f.radiance, f.guides(), workspace, out);
    });
    return out;
}

/// The largest relative difference between the filter's output and the formula in double.
double worstAgainstTheFormula(const RandomFrame& f, const Image& out)
{
    const auto want = referencePostFilter(f.radiance, f.albedo, f.normal, f.depth,
        afn::afnet::kPostFilterSigmaLuminance / 2); // no noise guide
    double worst = 0;
    for (std::size_t k = 0; k < want.size(); ++k)
        worst = std::max(worst, std::fabs(out.data()[k] - want[k]) / std::max(want[k], 1e-3));
    return worst;
}

} // namespace

// A frame whose width is not a multiple of the 16-pixel runs: every run kind (interior, border,
// short tail) against the formula in double. The filter's exp is a polynomial (relative error
// < 3e-6) and it sums in float: 5e-5 relative.
TEST(AfnPostFilter, MatchesTheFormulaOnEveryRunKind)
{
    const RandomFrame f(53, 19, 5);
    const double worst = worstAgainstTheFormula(f, filterWithThreads(f, 1));
    EXPECT_LT(worst, 5e-5);
    std::printf("post-filter against the formula: max relative error %.3g\n", worst);
}

// A frame tall enough for several bands (one per thread, each computing the rows of the earlier
// half-passes its first rows read): every row against the formula, the rows next to the bands'
// edges included, and the same bits whatever the thread count.
TEST(AfnPostFilter, BandsOfRowsGiveTheFormulaAndTheSameBitsWhateverTheThreadCount)
{
    const RandomFrame f(37, 5 * 64 + 11, 9);
    const Image one = filterWithThreads(f, 1);
    EXPECT_LT(worstAgainstTheFormula(f, one), 5e-5);
    for (int threads : { 2, 3, 5, 16 }) {
        const Image many = filterWithThreads(f, threads);
        ASSERT_EQ(many.size(), one.size());
        EXPECT_LT(worstAgainstTheFormula(f, many), 5e-5) << threads << " threads";
        for (std::size_t i = 0; i < one.size(); ++i)
            ASSERT_EQ(many.data()[i], one.data()[i]) << threads << " threads, value " << i;
    }
}
