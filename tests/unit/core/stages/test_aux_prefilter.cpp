// SPDX-License-Identifier: Apache-2.0
// The aux prefilter (lib/core/stages/aux_prefilter.h) through every method that demodulates:
//   - noisy albedo (per-pixel random, irradiance smooth) gives an output error within a small
//     factor (2x) of the same sequence with the clean (expected) albedo, where remodulating by the
//     raw albedo used to return (ta, svgf, afn) or keep much of (bmfr) the input noise;
//   - clean albedo: "auto" decides clean and the output is bit-identical to "clean";
//   - the speckle estimate separates the two; the bad-input rule still holds in noisy mode.
#include "stages/aux_noise.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {

using afn::Image;
using methods_test::Buffers;
using methods_test::makeImage;
using methods_test::runFrame;

constexpr int kW = 64, kH = 48, kFrames = 8;

/// The methods that demodulate (afn only when the build embeds its weights).
std::vector<std::string> methods()
{
    std::vector<std::string> m = { "ta", "svgf", "bmfr" };
    if (const afn::FilterType* t = afn::findFilterType("afn"); t && t->ready)
        m.push_back("afn");
    return m;
}

float irradiance(int x, int y)
{
    return 0.5f + 0.3f * std::sin(x / 9.0f) * std::cos(y / 7.0f);
}

/// Expected albedo: two flat halves (a clean, piecewise constant texture).
float cleanAlbedo(int x, int, int c)
{
    return x < kW / 2 ? 0.5f : 0.3f + 0.1f * c;
}

struct Sequence {
    std::vector<Image> color, noisyAlbedo;
    Image reference;
};

/// Frame k: albedo sample a = expected * (0.2 + 1.6 u), u uniform per pixel and frame (as an AOV
/// that follows a random bounce); colour = irradiance * a (the same path), plus 10 % noise.
Sequence makeSequence()
{
    Sequence s;
    methods_test::Lcg rng { 12345u };
    for (int k = 0; k < kFrames; ++k) {
        Image a(kW, kH, 3), c(kW, kH, 3);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float u = 0.5f + 0.5f * rng.next();
                const float n = 1.0f + 0.1f * rng.next();
                for (int ch = 0; ch < 3; ++ch) {
                    a(x, y, ch) = std::fmin(cleanAlbedo(x, y, ch) * (0.2f + 1.6f * u), 1.0f);
                    c(x, y, ch) = irradiance(x, y) * a(x, y, ch) * n;
                }
            }
        s.noisyAlbedo.push_back(a);
        s.color.push_back(c);
    }
    // The expectation of the clipped albedo sample is what the colour averages to.
    s.reference = makeImage(kW, kH, 3, [&](int x, int y, int ch) {
        double sum = 0.0;
        const int n = 1000;
        for (int i = 0; i < n; ++i) {
            const double u = (i + 0.5) / n;
            sum += std::fmin(cleanAlbedo(x, y, ch) * (0.2 + 1.6 * u), 1.0);
        }
        return static_cast<float>(irradiance(x, y) * sum / n);
    });
    return s;
}

/// Run the sequence through a method with albedo per frame from `albedo(k)`; RMSE of the last
/// frame against the reference.
template <typename AlbedoOf>
double runSequence(const std::string& method, const char* aux, const Sequence& s, AlbedoOf albedo,
    Image* out = nullptr, bool* noisy = nullptr, int spp = 0, bool* grainLimited = nullptr)
{
    auto f = afn::createFilter(method);
    f->params().setString("aux", aux);
    f->params().setNumber(AFN_PARAM_SPP, spp, AFN_PARAM_INT);
    Buffers b;
    b.normal = makeImage(kW, kH, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    b.depth = makeImage(kW, kH, 1, [](int, int, int) { return 3.0f; });
    for (int k = 0; k < kFrames; ++k) {
        b.color = s.color[k];
        b.albedo = albedo(k);
        runFrame(*f, b);
    }
    if (out)
        *out = b.out;
    if (noisy)
        *noisy = f->auxReport().noisy;
    if (grainLimited)
        *grainLimited = f->auxReport().grainLimited;
    return methods_test::rmse(b.out, s.reference);
}

Image expectedAlbedo(const Sequence& s)
{
    // The clean albedo a renderer's first-hit AOV would give: the expectation of the samples.
    return makeImage(
        kW, kH, 3, [&](int x, int y, int ch) { return s.reference(x, y, ch) / irradiance(x, y); });
}

TEST(AuxPrefilter, SpeckleShareSeparatesNoisyFromClean)
{
    const Sequence s = makeSequence();
    const double noisy = afn::speckleShare(s.noisyAlbedo[0].view(), afn::AuxKind::Albedo);
    const double clean = afn::speckleShare(expectedAlbedo(s).view(), afn::AuxKind::Albedo);
    EXPECT_GT(noisy, 0.2);
    EXPECT_EQ(clean, 0.0);
    EXPECT_GT(noisy, afn::kAuxNoisyShare);
}

TEST(AuxPrefilter, NoisyAlbedoErrorWithinSmallFactorOfClean)
{
    const Sequence s = makeSequence();
    const Image clean = expectedAlbedo(s);
    const double input = methods_test::rmse(s.color.back(), s.reference);
    for (const std::string& m : methods()) {
        bool decided = false;
        const double withClean = runSequence(m, "clean", s, [&](int) { return clean; });
        const double withNoisy = runSequence(
            m, "auto", s, [&](int k) { return s.noisyAlbedo[k]; }, nullptr, &decided);
        const double before = runSequence(m, "clean", s, [&](int k) { return s.noisyAlbedo[k]; });
        std::printf("%s: RMSE noisy albedo %.4f (raw remodulation %.4f), clean albedo %.4f, input "
                    "%.4f\n",
            m.c_str(), withNoisy, before, withClean, input);
        EXPECT_TRUE(decided) << m << ": auto should find the albedo noisy";
        EXPECT_LT(withNoisy, 2.0 * withClean + 0.005)
            << m << ": noisy " << withNoisy << " clean " << withClean << " input " << input;
        EXPECT_LT(withNoisy, 0.8 * before)
            << m << ": remodulating by the raw albedo gave " << before;
    }
}

TEST(AuxPrefilter, CleanAlbedoAutoIsBitIdenticalToClean)
{
    const Sequence s = makeSequence();
    const Image clean = expectedAlbedo(s);
    for (const std::string& m : methods()) {
        Image autoOut, cleanOut;
        bool decided = true;
        runSequence(
            m, "auto", s, [&](int) { return clean; }, &autoOut, &decided);
        runSequence(
            m, "clean", s, [&](int) { return clean; }, &cleanOut);
        EXPECT_FALSE(decided) << m;
        EXPECT_TRUE(methods_test::bitEqual(autoOut, cleanOut)) << m;
    }
}

// From AFN_AUX_TRUSTED_SPP samples per pixel aux=auto does not prefilter, speckle or not (the
// speckle test cannot tell noise from fine texture; stages/aux_prefilter.h): where it finds
// speckle it only limits the albedo's grain over time (each value within 10 % of the given one),
// which on this albedo of independent per-frame noise brings the error below aux=clean's; one
// sample fewer, the same speckle still decides noisy; aux=noisy is still obeyed; a clean albedo
// at 16 spp is used exactly as given.
TEST(AuxPrefilter, FromTheTrustedSampleCountAutoOnlyLimitsTheAlbedosGrain)
{
    const Sequence s = makeSequence();
    const Image expected = expectedAlbedo(s);
    auto noisyAlbedo = [&](int k) { return s.noisyAlbedo[k]; };
    for (const std::string& m : methods()) {
        bool decided = true, grain = false;
        const double limited = runSequence(
            m, "auto", s, noisyAlbedo, nullptr, &decided, AFN_AUX_TRUSTED_SPP, &grain);
        EXPECT_FALSE(decided) << m << ": at " << AFN_AUX_TRUSTED_SPP << " spp";
        EXPECT_TRUE(grain) << m;
        const double clean
            = runSequence(m, "clean", s, noisyAlbedo, nullptr, nullptr, AFN_AUX_TRUSTED_SPP);
        std::printf("%s at %d spp: RMSE grain-limited %.5f, clean %.5f\n", m.c_str(),
            AFN_AUX_TRUSTED_SPP, limited, clean);
        EXPECT_LT(limited, clean) << m;
        decided = false;
        runSequence(m, "auto", s, noisyAlbedo, nullptr, &decided, AFN_AUX_TRUSTED_SPP - 1);
        EXPECT_TRUE(decided) << m << ": at " << AFN_AUX_TRUSTED_SPP - 1 << " spp";
        decided = false;
        runSequence(m, "noisy", s, noisyAlbedo, nullptr, &decided, 4 * AFN_AUX_TRUSTED_SPP);
        EXPECT_TRUE(decided) << m << ": aux=noisy at any count";
        Image autoOut, cleanOut;
        grain = true;
        runSequence(
            m, "auto", s, [&](int) { return expected; }, &autoOut, nullptr, AFN_AUX_TRUSTED_SPP,
            &grain);
        runSequence(
            m, "clean", s, [&](int) { return expected; }, &cleanOut, nullptr, AFN_AUX_TRUSTED_SPP);
        EXPECT_FALSE(grain) << m << ": no speckle, nothing to limit";
        EXPECT_TRUE(methods_test::bitEqual(autoOut, cleanOut)) << m;
    }
}

TEST(AuxPrefilter, ForcedNoisyOnCleanAlbedoIsNotWorse)
{
    const Sequence s = makeSequence();
    const Image clean = expectedAlbedo(s);
    for (const std::string& m : methods()) {
        const double asClean = runSequence(m, "clean", s, [&](int) { return clean; });
        const double asNoisy = runSequence(m, "noisy", s, [&](int) { return clean; });
        EXPECT_LE(asNoisy, asClean * 1.05 + 1e-6) << m; // no speckle: the albedo stays as given
    }
}

TEST(AuxPrefilter, AnIsolatedSpeckleInACleanWindowLeavesNoDot)
{
    // The expected albedo with a few isolated black samples per frame (1 in 64 pixels, so a 5x5
    // window holds 0-2 and its share alone would keep them), against the same sequence with the
    // expected albedo everywhere: in noisy mode no method may give those pixels back as dark
    // dots. Without the per-pixel rule the output there was the albedo floor's 1/32 of the
    // irradiance, a few percent of the other run's; now it is close to it.
    const Sequence s = makeSequence();
    const Image clean = expectedAlbedo(s);
    auto speckled = [&](int k) {
        Image a = clean;
        for (int y = 2 + k % 4; y < kH - 2; y += 8)
            for (int x = 2 + (k * 3) % 8; x < kW - 2; x += 8)
                for (int c = 0; c < 3; ++c)
                    a(x, y, c) = 0.0f;
        return a;
    };
    const Image last = speckled(kFrames - 1);
    for (const std::string& m : methods()) {
        Image out, without;
        bool noisy = false;
        runSequence(m, "noisy", s, speckled, &out, &noisy);
        runSequence(
            m, "noisy", s, [&](int) { return clean; }, &without);
        ASSERT_TRUE(noisy) << m;
        double worst = 1.0;
        int dots = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                if (last(x, y, 0) == 0.0f) {
                    ++dots;
                    for (int c = 0; c < 3; ++c)
                        worst = std::min(worst, double(out(x, y, c)) / without(x, y, c));
                }
        ASSERT_GT(dots, 20) << m;
        EXPECT_GT(worst, 0.7) << m << ": darkest speckle pixel / the same pixel without speckle";
    }
}

TEST(AuxPrefilter, BadAlbedoCountedAndReplacedInNoisyMode)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const Sequence s = makeSequence();
    for (const std::string& m : methods()) {
        auto f = afn::createFilter(m);
        f->params().setString("aux", "noisy");
        Buffers b;
        for (int k = 0; k < 3; ++k) {
            b.color = s.color[k];
            b.albedo = s.noisyAlbedo[k];
            b.albedo(3, 4, 0) = nan;
            b.albedo(5, 6, 1) = inf;
            b.albedo(7, 8, 2) = -inf;
            b.albedo(9, 9, 0) = -2.0f;
            runFrame(*f, b);
            EXPECT_EQ(f->lastStats().nonFinite, 3) << m;
            EXPECT_TRUE(methods_test::allFiniteNonNegative(b.out)) << m;
            EXPECT_TRUE(f->auxReport().noisy) << m;
        }
    }
}

// A history decided clean measures its speckle shares only when asked for (after the frame, on
// the inputs as given, of which the normal and depth have become the reprojection's history);
// aux=noisy measures them on every frame before it prefilters. Both must report the same shares
// for every frame, for every method that demodulates: albedo, normals and depth with speckle
// that differs from frame to frame (a share read from the previous frame's buffers fails).
TEST(AuxPrefilter, ACleanHistoryReportsEachFramesSpeckleShares)
{
    const Sequence s = makeSequence();
    std::vector<Image> normals, depths;
    methods_test::Lcg rng { 777u };
    for (int k = 0; k < kFrames; ++k) {
        const float share = 0.02f * static_cast<float>(k + 1); // a different count per frame
        normals.push_back(
            makeImage(kW, kH, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; }));
        depths.push_back(makeImage(kW, kH, 1, [](int, int, int) { return 3.0f; }));
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                if (0.5f + 0.5f * rng.next() < share) { // a unit normal of another direction
                    normals[k](x, y, 0) = 0.6f;
                    normals[k](x, y, 2) = 0.8f;
                }
                if (0.5f + 0.5f * rng.next() < share)
                    depths[k](x, y, 0) = 6.0f;
            }
    }
    int checked = 0;
    for (const afn::FilterType& t : afn::filterTypes()) {
        if (!t.ready || !t.stages.demodulate)
            continue;
        auto lazy = afn::createFilter(t.name), eager = afn::createFilter(t.name);
        lazy->params().setString("aux", "clean");
        eager->params().setString("aux", "noisy");
        Buffers a, b;
        for (int k = 0; k < kFrames; ++k) {
            for (Buffers* x : { &a, &b }) {
                x->color = s.color[k];
                x->albedo = s.noisyAlbedo[k];
                x->normal = normals[k];
                x->depth = depths[k];
            }
            runFrame(*lazy, a);
            runFrame(*eager, b);
            const afn::AuxReport& r = lazy->auxReport();
            const afn::AuxReport& e = eager->auxReport();
            EXPECT_FALSE(r.noisy) << t.name;
            EXPECT_TRUE(e.noisy) << t.name;
            EXPECT_GT(r.albedoSpeckle, 0.2) << t.name << " frame " << k;
            EXPECT_GT(r.normalSpeckle, 0.0) << t.name << " frame " << k;
            EXPECT_GT(r.depthSpeckle, 0.0) << t.name << " frame " << k;
            EXPECT_EQ(r.albedoSpeckle, e.albedoSpeckle) << t.name << " frame " << k;
            EXPECT_EQ(r.normalSpeckle, e.normalSpeckle) << t.name << " frame " << k;
            EXPECT_EQ(r.depthSpeckle, e.depthSpeckle) << t.name << " frame " << k;
            EXPECT_EQ(lazy->auxReport().normalSpeckle, r.normalSpeckle) << "asked twice";
        }
        ++checked;
    }
    EXPECT_GE(checked, 3);
}

TEST(AuxNoise, FlagsAreTheFullMinimumOverTheNeighbours)
{
    // speckleFlags stops at the first neighbour within the threshold; the flags must be those of
    // the literal rule: min over all comparable neighbours > threshold (normals, 30 % noisy).
    const int w = 19, h = 11;
    methods_test::Lcg rng { 42u };
    Image n = makeImage(w, h, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (rng.next() > 0.4f) {
                float v[3] = { rng.next(), rng.next(), rng.next() }, l = 0.0f;
                for (float c : v)
                    l += c * c;
                for (int c = 0; c < 3; ++c)
                    n(x, y, c) = v[c] / std::sqrt(l);
            }
    Image flags;
    const std::int64_t count = afn::speckleFlags(n.view(), afn::AuxKind::Normal, flags);
    std::int64_t want = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float best = std::numeric_limits<float>::infinity();
            for (int qy = y - 1; qy <= y + 1; ++qy)
                for (int qx = x - 1; qx <= x + 1; ++qx) {
                    if ((qx == x && qy == y) || qx < 0 || qy < 0 || qx >= w || qy >= h)
                        continue;
                    float d2 = 0.0f;
                    for (int c = 0; c < 3; ++c)
                        d2 += (n(x, y, c) - n(qx, qy, c)) * (n(x, y, c) - n(qx, qy, c));
                    best = std::fmin(best, std::sqrt(d2));
                }
            const bool speckle = best > afn::AuxNoiseThresholds::normal;
            EXPECT_EQ(flags(x, y, 0), speckle ? 1.0f : 0.0f) << x << "," << y;
            want += speckle;
        }
    EXPECT_EQ(count, want);
    EXPECT_EQ(afn::speckleCount(n.view(), afn::AuxKind::Normal), want);
    EXPECT_GT(want, 0);
    EXPECT_LT(want, static_cast<std::int64_t>(w) * h);
}

} // namespace
