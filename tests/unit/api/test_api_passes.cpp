// SPDX-License-Identifier: Apache-2.0
// Light-path passes denoised with the beauty ("pass.<name>", "passFactor.<name>",
// "passOutput.<name>"; lib/core/stages/pass_transfer.h): the denoised passes add up to the
// denoised beauty for every method, a constant scene stays exact, the history is used, and every
// wrong binding is an error naming the image.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr int kW = 40, kH = 28, kN = kW * kH;

/// A noisy frame whose beauty is exactly diffuse x colour + glossy + emission (three passes, one
/// with a factor, which is 0 in two columns), with a left/right material edge and a normal/depth
/// edge.
struct PassFrame {
    std::vector<float> beauty, diffuse, colour, glossy, emission, normal, depth, motion;
};

PassFrame makeFrame(unsigned seed, bool noisy, bool spike = true)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 2.0f);
    PassFrame f;
    for (auto* v : { &f.beauty, &f.diffuse, &f.colour, &f.glossy, &f.emission, &f.normal })
        v->assign(kN * 3, 0.0f);
    f.depth.assign(kN, 0.0f);
    f.motion.assign(kN * 2, 0.0f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const int i = y * kW + x;
            const bool left = x < kW / 2;
            const float n1 = noisy ? u(rng) : 1.0f, n2 = noisy ? u(rng) : 1.0f;
            for (int c = 0; c < 3; ++c) {
                // Columns 12-13 have no diffuse colour: their diffuse light adds nothing.
                f.colour[i * 3 + c] = x == 12 || x == 13 ? 0.0f : left ? 0.8f : 0.3f + 0.1f * c;
                f.diffuse[i * 3 + c] = 0.6f * n1;
                f.glossy[i * 3 + c] = (left ? 0.1f : 0.4f) * n2;
                f.emission[i * 3 + c] = spike && x == 5 && y == 5 ? 2.0f : 0.0f;
                f.beauty[i * 3 + c] = f.diffuse[i * 3 + c] * f.colour[i * 3 + c]
                    + f.glossy[i * 3 + c] + f.emission[i * 3 + c];
            }
            f.normal[i * 3 + (left ? 2 : 0)] = 1.0f;
            f.depth[i] = left ? 2.0f : 5.0f;
        }
    return f;
}

struct PassOutputs {
    std::vector<float> beauty, diffuse, glossy, emission;
};

/// Run `frames` frames of `method` with the three passes bound; the last frame's outputs.
PassOutputs runPasses(
    const char* method, int frames, bool noisy, bool inPlace = false, bool spike = true)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter(method);
    PassOutputs out;
    for (auto* v : { &out.beauty, &out.diffuse, &out.glossy, &out.emission })
        v->assign(kN * 3, -1.0f);
    for (int t = 0; t < frames; ++t) {
        PassFrame f = makeFrame(100 + t, noisy, spike);
        filter.setImage(AFN_IMAGE_COLOR, f.beauty.data(), afn::Format::Float3, kW, kH);
        filter.setImage(AFN_IMAGE_ALBEDO, f.colour.data(), afn::Format::Float3, kW, kH);
        filter.setImage(AFN_IMAGE_NORMAL, f.normal.data(), afn::Format::Float3, kW, kH);
        filter.setImage(AFN_IMAGE_DEPTH, f.depth.data(), afn::Format::Float, kW, kH);
        filter.setImage(AFN_IMAGE_MOTION, f.motion.data(), afn::Format::Float2, kW, kH);
        filter.setImage(AFN_IMAGE_OUTPUT, out.beauty.data(), afn::Format::Float3, kW, kH);
        filter.setImage("pass.diffuse", f.diffuse.data(), afn::Format::Float3, kW, kH);
        filter.setImage("passFactor.diffuse", f.colour.data(), afn::Format::Float3, kW, kH);
        filter.setImage("pass.glossy", f.glossy.data(), afn::Format::Float3, kW, kH);
        filter.setImage("pass.emission", f.emission.data(), afn::Format::Float3, kW, kH);
        if (inPlace) {
            filter.setImage("passOutput.diffuse", f.diffuse.data(), afn::Format::Float3, kW, kH);
            filter.setImage("passOutput.glossy", f.glossy.data(), afn::Format::Float3, kW, kH);
            filter.setImage("passOutput.emission", f.emission.data(), afn::Format::Float3, kW, kH);
        } else {
            filter.setImage("passOutput.diffuse", out.diffuse.data(), afn::Format::Float3, kW, kH);
            filter.setImage("passOutput.glossy", out.glossy.data(), afn::Format::Float3, kW, kH);
            filter.setImage(
                "passOutput.emission", out.emission.data(), afn::Format::Float3, kW, kH);
        }
        filter.commit();
        filter.execute();
        std::string message;
        EXPECT_EQ(device.getError(&message), afn::Error::None) << method << ": " << message;
        if (inPlace) {
            out.diffuse = f.diffuse;
            out.glossy = f.glossy;
            out.emission = f.emission;
        }
    }
    return out;
}

/// Largest |diffuse' x colour + glossy' + emission' - beauty'| relative to (1 + |beauty'|).
double recompositionError(const PassOutputs& o)
{
    const PassFrame f = makeFrame(0, false); // the colour factor does not depend on the seed
    double worst = 0.0;
    for (int i = 0; i < kN * 3; ++i) {
        const double sum = o.diffuse[i] * f.colour[i] + o.glossy[i] + o.emission[i];
        worst = std::max(worst, std::abs(sum - o.beauty[i]) / (1.0 + std::abs(o.beauty[i])));
    }
    return worst;
}

/// RMS of (value - clean value) of a pass.
double rmsError(const std::vector<float>& v, const std::vector<float>& clean)
{
    double s = 0.0;
    for (int i = 0; i < kN * 3; ++i)
        s += (v[i] - clean[i]) * (v[i] - clean[i]);
    return std::sqrt(s / (kN * 3));
}

} // namespace

TEST(ApiPasses, DenoisedPassesAddUpToTheDenoisedBeautyForEveryMethod)
{
    for (const char* method : { "identity", "ta", "svgf", "bmfr", "afn" }) {
        const PassOutputs o = runPasses(method, 3, true);
        EXPECT_LT(recompositionError(o), 1e-5) << method;
    }
}

TEST(ApiPasses, NoisyPassesComeOutAsCloseToTheirCleanValuesAsTheBeauty)
{
    // The passes follow the beauty's denoising: each is closer to its clean value by about the
    // beauty's own factor (ta over 8 frames of a static scene).
    const PassFrame clean = makeFrame(0, false);
    const PassFrame noisy = makeFrame(107, true);
    const PassOutputs o = runPasses("ta", 8, true);
    const double beautyGain
        = rmsError(o.beauty, clean.beauty) / rmsError(noisy.beauty, clean.beauty);
    const double diffuseGain
        = rmsError(o.diffuse, clean.diffuse) / rmsError(noisy.diffuse, clean.diffuse);
    const double glossyGain
        = rmsError(o.glossy, clean.glossy) / rmsError(noisy.glossy, clean.glossy);
    EXPECT_LT(beautyGain, 0.6);
    EXPECT_LT(diffuseGain, beautyGain + 0.1);
    EXPECT_LT(glossyGain, beautyGain + 0.1);
}

TEST(ApiPasses, AConstantSceneStaysExact)
{
    // No noise, two constant halves split by a normal and depth edge: identity returns the
    // beauty, and each pass's share is its own: the passes come out as they went in.
    const PassFrame clean = makeFrame(0, false, false);
    const PassOutputs o = runPasses("identity", 2, false, false, false);
    for (int i = 0; i < kN * 3; ++i) {
        ASSERT_NEAR(o.diffuse[i], clean.diffuse[i], 1e-4f * (1.0f + clean.diffuse[i])) << i;
        ASSERT_NEAR(o.glossy[i], clean.glossy[i], 1e-4f * (1.0f + clean.glossy[i])) << i;
    }
}

TEST(ApiPasses, OutputsMayBeThePassesOwnBuffers)
{
    const PassOutputs apart = runPasses("ta", 2, true, false);
    const PassOutputs inPlace = runPasses("ta", 2, true, true);
    EXPECT_EQ(apart.diffuse, inPlace.diffuse);
    EXPECT_EQ(apart.glossy, inPlace.glossy);
    EXPECT_EQ(apart.emission, inPlace.emission);
}

TEST(ApiPasses, WrongBindingsAreErrorsNamingTheImage)
{
    std::vector<float> a(kN * 3, 0.5f), b(kN * 3), c(kN * 3), two(kN * 2, 0.0f);
    auto commitWith
        = [&](const std::vector<std::pair<std::string, afn::Format>>& images, bool output) {
              afn::DeviceRef device = afn::newDevice();
              device.commit();
              afn::FilterRef filter = device.newFilter("ta");
              filter.setImage(AFN_IMAGE_COLOR, a.data(), afn::Format::Float3, kW, kH);
              if (output)
                  filter.setImage(AFN_IMAGE_OUTPUT, b.data(), afn::Format::Float3, kW, kH);
              for (const auto& [name, format] : images)
                  filter.setImage(name.c_str(),
                      format == afn::Format::Float2 ? two.data() : c.data(), format, kW, kH);
              filter.commit();
              std::string message;
              const afn::Error e = device.getError(&message);
              return e == afn::Error::None ? std::string() : message;
          };
    const afn::Format f3 = afn::Format::Float3;
    EXPECT_EQ(commitWith({ { "pass.x", f3 }, { "passOutput.x", f3 } }, true), "");
    EXPECT_NE(commitWith({ { "pass.x", f3 } }, true).find("passOutput.x"), std::string::npos);
    EXPECT_NE(commitWith({ { "passOutput.x", f3 } }, true).find("has no pass 'pass.x'"),
        std::string::npos);
    EXPECT_NE(commitWith({ { "pass.x", f3 }, { "passOutput.x", f3 }, { "passFactor.y", f3 } }, true)
                  .find("passFactor.y"),
        std::string::npos);
    EXPECT_NE(commitWith({ { "pass.x", afn::Format::Float2 }, { "passOutput.x", f3 } }, true)
                  .find("3 channels"),
        std::string::npos);
    EXPECT_NE(
        commitWith({ { "pass.x", f3 }, { "passOutput.x", f3 } }, false).find("bind 'output' too"),
        std::string::npos);
    // A bare prefix is not a pass.
    EXPECT_NE(commitWith({ { "pass.", f3 } }, true).find("unknown image"), std::string::npos);
}
