// SPDX-License-Identifier: Apache-2.0
// Work skipping through the OFX plugin (docs/work-skipping.md): a Mask clip that leaves out the
// right half of the frame; with the "skip" parameter on (the default) every method's pixels
// inside the mask are bit-identical to skip off on every frame, and for svgf and bmfr the pixels
// outside it differ (they took the cheap path).
#include "plugin_session.h"

#include <gtest/gtest.h>

using namespace ofxhost;
using namespace ofxtest;

namespace {

constexpr int kMaskColumns = 20; ///< mask = 1 on columns [0, 20) of the 40-pixel-wide frame

ClipSource maskSource(const Sequence& seq)
{
    ClipSource s = seq.source("depth"); // same size, origin, frames; 1 component
    s.frame = [seq](double time, double scale, std::vector<float>& px) {
        if (time < seq.firstFrame || time > seq.firstFrame + seq.numFrames - 1)
            return false;
        const int w = static_cast<int>(seq.width * scale), h = static_cast<int>(seq.height * scale);
        px.assign(static_cast<std::size_t>(w) * h, 0.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w && x < kMaskColumns * scale; ++x)
                px[static_cast<std::size_t>(y) * w + x] = 1.0f;
        return true;
    };
    return s;
}

/// Every frame of `method` with the Mask clip connected and skip on or off.
std::vector<std::vector<float>> renderAll(
    Session& s, const ClipSource& mask, const std::string& method, bool skip)
{
    std::map<std::string, const ClipSource*> inputs
        = { { "Source", &s.sources["color"] }, { "Mask", &mask } };
    for (size_t i = 0; i < kAllAux.size(); ++i)
        inputs[kClipOf[i]] = &s.sources[kAllAux[i]];
    OfxStatus st = kOfxStatFailed;
    auto inst = s.host.createInstance(*s.general, kOfxImageEffectContextGeneral, inputs, &st);
    EXPECT_EQ(st, kOfxStatOK);
    EXPECT_EQ(s.host.setParam(inst.get(), "method", methodIndex(method)), kOfxStatOK);
    if (const std::string w = testWeightsFor(method); !w.empty())
        EXPECT_EQ(s.host.setParam(inst.get(), "weights", w), kOfxStatOK);
    EXPECT_EQ(s.host.setParam(inst.get(), "skip", skip ? 1 : 0), kOfxStatOK);
    std::vector<std::vector<float>> out;
    for (int k = 0; k < s.seq.numFrames; ++k)
        out.push_back(s.render(inst.get(), s.seq.firstFrame + k));
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    return out;
}

} // namespace

TEST(PluginSkip, MaskClipLeavesMaskedPixelsBitIdentical)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const ClipSource mask = maskSource(s.seq);
    for (const std::string& m : methodsUnderTest()) {
        SCOPED_TRACE("method " + m);
        const auto on = renderAll(s, mask, m, true);
        const auto off = renderAll(s, mask, m, false);
        bool outsideDiffers = false;
        for (size_t k = 0; k < on.size(); ++k) {
            ASSERT_EQ(on[k].size(), off[k].size());
            for (int y = 0; y < s.seq.height; ++y)
                for (int x = 0; x < s.seq.width; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const size_t i = (static_cast<size_t>(y) * s.seq.width + x) * 4 + c;
                        if (x < kMaskColumns)
                            ASSERT_EQ(on[k][i], off[k][i]) << "frame " << k << " " << x << "," << y;
                        else
                            outsideDiffers = outsideDiffers || on[k][i] != off[k][i];
                    }
        }
        if (m == "svgf" || m == "bmfr")
            EXPECT_TRUE(outsideDiffers) << "nothing was skipped";
    }
}
