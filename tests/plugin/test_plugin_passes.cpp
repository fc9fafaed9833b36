// SPDX-License-Identifier: Apache-2.0
// Light-path passes through the OFX plugin (docs/passes.md): with Output = Pass the effect shows
// the Pass clip denoised with Source. A pass that is the whole beauty comes out as the denoised
// beauty, a pass that is a quarter of it as a quarter; Output = Pass without a Pass clip fails.
#include "plugin_session.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ofxhost;
using namespace ofxtest;

namespace {

/// Source scaled by `k` (RGB; alpha kept), as a clip of its own.
ClipSource scaledSource(const ClipSource& source, float k)
{
    ClipSource s = source;
    const auto frame = source.frame;
    const int comps = source.components;
    s.frame = [frame, k, comps](double time, double scale, std::vector<float>& px) {
        if (!frame(time, scale, px))
            return false;
        for (std::size_t i = 0; i < px.size(); ++i)
            if (comps < 4 || i % 4 != 3)
                px[i] *= k;
        return true;
    };
    return s;
}

/// Every frame of svgf with every input, the Pass clip connected when `pass` is set.
std::vector<std::vector<float>> renderAll(
    Session& s, const ClipSource* pass, bool outputPass, OfxStatus* status = nullptr)
{
    std::map<std::string, const ClipSource*> inputs = { { "Source", &s.sources["color"] } };
    for (size_t i = 0; i < kAllAux.size(); ++i)
        inputs[kClipOf[i]] = &s.sources[kAllAux[i]];
    if (pass)
        inputs["Pass"] = pass;
    OfxStatus st = kOfxStatFailed;
    auto inst = s.host.createInstance(*s.general, kOfxImageEffectContextGeneral, inputs, &st);
    EXPECT_EQ(st, kOfxStatOK);
    EXPECT_EQ(s.host.setParam(inst.get(), "method", methodIndex("svgf")), kOfxStatOK);
    EXPECT_EQ(s.host.setParam(inst.get(), "outputPass", outputPass ? 1 : 0), kOfxStatOK);
    std::vector<std::vector<float>> out;
    for (int k = 0; k < s.seq.numFrames; ++k) {
        if (status) {
            Frame frame;
            *status = s.host.renderFrame(inst.get(), s.seq.firstFrame + k, 1.0, 1, frame);
            if (*status != kOfxStatOK)
                break;
            out.push_back(frame.rgba);
        } else {
            out.push_back(s.render(inst.get(), s.seq.firstFrame + k));
        }
    }
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    return out;
}

} // namespace

TEST(PluginPasses, APassDenoisedWithSourceIsItsShareOfTheDenoisedBeauty)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const auto beauty = renderAll(s, nullptr, false);
    const ClipSource whole = scaledSource(s.sources["color"], 1.0f);
    const ClipSource quarter = scaledSource(s.sources["color"], 0.25f);
    const auto asPass = renderAll(s, &whole, true);
    const auto quarterPass = renderAll(s, &quarter, true);
    ASSERT_EQ(asPass.size(), beauty.size());
    ASSERT_EQ(quarterPass.size(), beauty.size());
    for (size_t k = 0; k < beauty.size(); ++k) {
        std::vector<float> quarterBeauty = beauty[k];
        for (size_t i = 0; i < quarterBeauty.size(); ++i)
            if (i % 4 != 3)
                quarterBeauty[i] *= 0.25f;
        EXPECT_TRUE(nearlyEqual(asPass[k], beauty[k])) << "frame " << k;
        EXPECT_TRUE(nearlyEqual(quarterPass[k], quarterBeauty)) << "frame " << k;
    }
    // Output = Beauty with a Pass clip connected: the beauty, unchanged.
    const auto beautyWithPass = renderAll(s, &quarter, false);
    for (size_t k = 0; k < beauty.size(); ++k)
        EXPECT_EQ(beautyWithPass[k], beauty[k]) << "frame " << k;
}

TEST(PluginPasses, OutputPassWithoutAPassClipFails)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    OfxStatus status = kOfxStatOK;
    const auto out = renderAll(s, nullptr, true, &status);
    EXPECT_NE(status, kOfxStatOK);
    EXPECT_TRUE(out.empty());
    std::string all;
    for (const std::string& m : s.host.messages())
        all += m + "\n";
    EXPECT_NE(all.find("the Pass clip is not connected"), std::string::npos) << all;
}
