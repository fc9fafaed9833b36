// SPDX-License-Identifier: Apache-2.0
// The detail restoration (stages/detail_restore.h): an output equal to the frame is left bit for
// bit; detail an output smoothed away comes back while noise an output removed does not; a firefly
// the output removed stays removed, a bright point the output kept stays; every result lies
// between the output and the frame; texture in the albedo is not taken for noise or detail; a
// colour already demodulated (BMFR dataset) is restored as irradiance; the auto rule; and through
// the filters: from 16 spp for svgf, from 32 spp for afn's 16-spp model, nothing at all below.
#include "stages/detail_restore.h"

#include "filter/registry.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using afn::DetailRestore;
using afn::Image;
using afn::RestoreSettings;
using methods_test::Lcg;
using methods_test::makeImage;

constexpr int W = 48, H = 40;

afn::ImageView viewOf(Image& img)
{
    afn::ImageView v;
    v.base = reinterpret_cast<const std::byte*>(img.data());
    v.width = img.width();
    v.height = img.height();
    v.channels = img.channels();
    v.pixelStride = static_cast<std::ptrdiff_t>(img.channels() * sizeof(float));
    v.rowStride = v.pixelStride * img.width();
    return v;
}

afn::Frame frameWith(const Image& albedo)
{
    afn::Frame f;
    f.width = W;
    f.height = H;
    f.albedo = albedo;
    return f;
}

/// Gaussian-like noise of standard deviation about `sigma` (sum of three uniforms).
Image noisy(const Image& clean, float sigma, std::uint32_t seed)
{
    Lcg rng { seed };
    return makeImage(W, H, 3, [&](int x, int y, int c) {
        const float n = (rng.next() + rng.next() + rng.next()) * sigma;
        return std::max(0.0f, clean(x, y, c) + n);
    });
}

double mse(const Image& a, const Image& b)
{
    const double r = methods_test::rmse(a, b);
    return r * r;
}

Image restored(Image frame, Image output, const Image& albedo = Image())
{
    DetailRestore r;
    r.run(frame, frameWith(albedo), RestoreSettings {}.noise, viewOf(output));
    return output;
}

} // namespace

TEST(DetailRestore, AutoFollowsTheSampleCountAndTheMethodsOwn)
{
    RestoreSettings s;
    EXPECT_FALSE(afn::restoreOn(s, 0, 1)); // unknown: as low
    EXPECT_FALSE(afn::restoreOn(s, 8, 1));
    EXPECT_TRUE(afn::restoreOn(s, 16, 1));
    EXPECT_FALSE(afn::restoreOn(s, 16, 16)); // afn's 16-spp model at its own count
    EXPECT_FALSE(afn::restoreOn(s, 31, 16));
    EXPECT_TRUE(afn::restoreOn(s, 32, 16));
    s.restore = RestoreSettings::Mode::Off;
    EXPECT_FALSE(afn::restoreOn(s, 1024, 1));
    s.restore = RestoreSettings::Mode::On;
    EXPECT_TRUE(afn::restoreOn(s, 1, 1));
}

TEST(DetailRestore, AnOutputEqualToTheFrameIsLeftBitForBit)
{
    const Image clean = makeImage(W, H, 3, [](int x, int y, int c) { return 0.1f * (x % 7) + c; });
    const Image frame = noisy(clean, 0.05f, 11u);
    const Image out = restored(frame, frame);
    EXPECT_TRUE(methods_test::bitEqual(out, frame));
}

TEST(DetailRestore, DetailComesBackAndNoiseDoesNot)
{
    // A vertical step 0.2 | 0.8 with noise of 0.01, and an output that smoothed it into a ramp
    // 9 pixels wide but removed the noise: the step comes back.
    const Image clean = makeImage(W, H, 3, [](int x, int, int) { return x < W / 2 ? 0.2f : 0.8f; });
    const Image frame = noisy(clean, 0.01f, 5u);
    const Image smoothed = makeImage(W, H, 3, [&](int x, int y, int c) {
        float s = 0.0f;
        for (int q = x - 4; q <= x + 4; ++q)
            s += clean(std::clamp(q, 0, W - 1), y, c);
        return s / 9.0f;
    });
    const double before = mse(smoothed, clean);
    const double after = mse(restored(frame, smoothed), clean);
    EXPECT_LT(after, 0.1 * before) << "before " << before << ", after " << after;

    // Flat 0.5 with noise of 0.05 and a perfect output: almost none of the noise comes back.
    const Image flat(W, H, 3, 0.5f);
    const Image noisyFlat = noisy(flat, 0.05f, 9u);
    const double noise = mse(noisyFlat, flat);
    DetailRestore r;
    Image out = flat, consumed = noisyFlat;
    r.run(consumed, frameWith(Image()), RestoreSettings {}.noise, viewOf(out));
    EXPECT_LT(mse(out, flat), 0.05 * noise);
    EXPECT_LT(r.restoredShare(), 0.01);
}

TEST(DetailRestore, AFireflyTheOutputRemovedStaysRemovedABrightPointItKeptStays)
{
    const Image flat(W, H, 3, 0.5f);
    Image frame = noisy(flat, 0.002f, 3u);
    for (int c = 0; c < 3; ++c) {
        frame(10, 10, c) = 50.0f; // a firefly: the output removed it
        frame(30, 20, c) = 50.0f; // a small light: the output kept most of it
    }
    Image output = flat;
    for (int c = 0; c < 3; ++c)
        output(30, 20, c) = 30.0f;
    const Image out = restored(frame, output);
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(out(10, 10, c), 0.52f);
        EXPECT_GE(out(30, 20, c), 30.0f);
        EXPECT_LE(out(30, 20, c), 50.0f);
    }
}

TEST(DetailRestore, EveryValueLiesBetweenTheOutputAndTheFrame)
{
    Lcg rng { 17u };
    const Image frame
        = makeImage(W, H, 3, [&](int, int, int) { return std::exp(3.0f * rng.next()); });
    const Image output
        = makeImage(W, H, 3, [&](int, int, int) { return std::exp(3.0f * rng.next()); });
    const Image albedo
        = makeImage(W, H, 3, [&](int, int, int) { return 0.5f + 0.5f * rng.next(); });
    const Image out = restored(frame, output, albedo);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                const float lo = std::min(frame(x, y, c), output(x, y, c));
                const float hi = std::max(frame(x, y, c), output(x, y, c));
                ASSERT_GE(out(x, y, c), lo * (1.0f - 1e-6f)) << x << "," << y;
                ASSERT_LE(out(x, y, c), hi * (1.0f + 1e-6f)) << x << "," << y;
            }
}

TEST(DetailRestore, TextureInTheAlbedoIsNeitherNoiseNorDetail)
{
    // A checker albedo (0.1 / 0.9, 2-pixel squares) lit by 1.0 with noise of 0.05 in the
    // irradiance; the output is the clean radiance. Demodulated, the residual is noise only:
    // nothing comes back. Without the albedo the checker itself would read as detail everywhere.
    const Image albedo
        = makeImage(W, H, 3, [](int x, int y, int) { return ((x / 2 + y / 2) % 2) ? 0.9f : 0.1f; });
    const Image lit = noisy(Image(W, H, 3, 1.0f), 0.05f, 21u);
    const Image frame
        = makeImage(W, H, 3, [&](int x, int y, int c) { return lit(x, y, c) * albedo(x, y, c); });
    DetailRestore r;
    Image out = albedo, consumed = frame;
    r.run(consumed, frameWith(albedo), RestoreSettings {}.noise, viewOf(out));
    EXPECT_LT(mse(out, albedo), 0.05 * mse(frame, albedo));
    EXPECT_LT(r.restoredShare(), 0.01);
}

TEST(DetailRestore, AColourAlreadyDemodulatedIsRestoredAsIrradiance)
{
    // The BMFR dataset's convention (Frame::colorDemodulated): the frame holds irradiance, the
    // output is radiance (irradiance times the albedo). The same step as above, smoothed by the
    // output, comes back in radiance; an output equal to the remodulated frame stays as it is.
    const Image albedo = makeImage(W, H, 3, [](int x, int, int) { return x % 2 ? 0.3f : 0.7f; });
    const Image clean = makeImage(W, H, 3, [](int x, int, int) { return x < W / 2 ? 0.2f : 0.8f; });
    const Image irradiance = noisy(clean, 0.01f, 5u);
    auto radiance = [&](const Image& irr) {
        return makeImage(
            W, H, 3, [&](int x, int y, int c) { return irr(x, y, c) * albedo(x, y, c); });
    };
    afn::Frame f = frameWith(albedo);
    f.colorDemodulated = true;
    DetailRestore r;
    Image consumed = irradiance, same = radiance(irradiance);
    r.run(consumed, f, RestoreSettings {}.noise, viewOf(same));
    const Image expected = radiance(irradiance);
    EXPECT_LT(methods_test::rmse(same, expected), 1e-6);
    const Image smoothed = radiance(makeImage(W, H, 3, [&](int x, int y, int c) {
        float s = 0.0f;
        for (int q = x - 4; q <= x + 4; ++q)
            s += clean(std::clamp(q, 0, W - 1), y, c);
        return s / 9.0f;
    }));
    Image out = smoothed;
    consumed = irradiance;
    r.run(consumed, f, RestoreSettings {}.noise, viewOf(out));
    EXPECT_LT(mse(out, radiance(clean)), 0.1 * mse(smoothed, radiance(clean)));
}

TEST(DetailRestore, FiltersRestoreFromTheirOwnSampleCount)
{
    // Fine vertical stripes of lighting (2 pixels wide) with a little noise: the filters smooth
    // some of them away.
    const Image stripes
        = makeImage(W, H, 3, [](int x, int, int) { return x % 4 < 2 ? 0.8f : 0.35f; });
    double restoredShare = 0.0;
    auto run = [&](const char* method, int spp, const char* restore) {
        auto f = afn::createFilter(method);
        f->params().setNumber("spp", spp, AFN_PARAM_INT);
        f->params().setString("restore", restore);
        methods_test::Buffers b;
        b.color = noisy(stripes, 0.02f, 13u);
        b.albedo = Image(W, H, 3, 0.5f);
        b.normal = makeImage(W, H, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
        b.depth = Image(W, H, 1, 2.0f);
        b.motion = Image(W, H, 2, 0.0f);
        methods_test::runFrame(*f, b);
        restoredShare = f->lastRestoredShare();
        return b.out;
    };
    // svgf (made for 1 spp): nothing below 16 spp; from 16 the stripes come back.
    EXPECT_TRUE(methods_test::bitEqual(run("svgf", 8, "auto"), run("svgf", 8, "off")));
    const Image svgfOff = run("svgf", 16, "off");
    EXPECT_EQ(restoredShare, 0.0);
    const Image svgfOn = run("svgf", 16, "auto");
    EXPECT_GT(restoredShare, 0.1);
    EXPECT_LT(mse(svgfOn, stripes), 0.5 * mse(svgfOff, stripes));
    // afn on the built-in models: the 16-spp model runs from 9 spp; restored from 32.
    EXPECT_TRUE(methods_test::bitEqual(run("afn", 16, "auto"), run("afn", 16, "off")));
    const Image afnOff = run("afn", 32, "off"), afnOn = run("afn", 32, "auto");
    EXPECT_LT(mse(afnOn, stripes), 0.5 * mse(afnOff, stripes));
}
