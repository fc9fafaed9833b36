// SPDX-License-Identifier: Apache-2.0
// The bounded history window (historyFrames), the start frame and the mix, through the test host
// over a 24-frame synthetic sequence: frames fetched after a jump, GetFramesNeeded, and results
// against the C API run over the same window.
#include "plugin_session.h"

#include <afn/afn.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

using namespace ofxhost;
using namespace ofxtest;

namespace {

Sequence longSequence()
{
    Sequence seq;
    seq.numFrames = 24;
    return seq;
}

/// The distinct times the Source clip was fetched at since the last call.
std::set<double> sourceFetches(OfxImageEffectStruct* inst)
{
    const std::vector<double> t = inst->clip("Source")->takeFetched();
    return std::set<double>(t.begin(), t.end());
}

std::set<double> range(int first, int last)
{
    std::set<double> out;
    for (int t = first; t <= last; ++t)
        out.insert(t);
    return out;
}

} // namespace

TEST(PluginHistory, AJumpReplaysAtMostHistoryFrames)
{
    Session s(Layout {}, longSequence());
    ASSERT_TRUE(s.loaded);
    const int n = 4, first = s.seq.firstFrame;
    for (const std::string& m : methodsUnderTest()) {
        SCOPED_TRACE("method " + m);
        auto inst = s.instance(m, kAllAux);
        ASSERT_EQ(s.host.setParam(inst.get(), "historyFrames", n), kOfxStatOK);
        // Jump to frame 20: frames 16..20 are fetched (N + 1), declared, and the result is the
        // filter run over exactly that window.
        const auto window = referenceFrames(s.seq, { m, true, 1.0, kAllAux, "", 0.0, 20.0 - n });
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 20), window[20 - first]));
        EXPECT_EQ(sourceFetches(inst.get()), range(20 - n, 20));
        EXPECT_EQ(inst->clip("Source")->framesNeeded, (std::vector<double> { 20.0 - n, 20.0 }));
        // The next frame continues the history (one fetch), so it still starts at frame 16.
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 21), window[21 - first]));
        EXPECT_EQ(sourceFetches(inst.get()), range(21, 21));
        // A jump back replays its own window.
        const auto back = referenceFrames(s.seq, { m, true, 1.0, kAllAux, "", 0.0, 9.0 - n });
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 9), back[9 - first]));
        EXPECT_EQ(sourceFetches(inst.get()), range(9 - n, 9));
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginHistory, AWindowCoveringTheShotEqualsTheSequentialRun)
{
    Session s(Layout { true, 2 }, longSequence());
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    const auto sequential = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
    auto inst = s.instance(m, kAllAux);
    // The default window (8) covers frame 9 of a shot starting at 1: equal to the sequential run.
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 9), sequential[8]));
    EXPECT_EQ(sourceFetches(inst.get()), range(1, 9));
    // A window above the shot's length replays from the first frame: equal again, at frame 23.
    ASSERT_EQ(s.host.setParam(inst.get(), "historyFrames", 1000), kOfxStatOK);
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 23, 1.0, 2), sequential[22]));
    EXPECT_EQ(sourceFetches(inst.get()), range(1, 23));
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHistory, FramesBeforeTheStartFrameAreNeverUsed)
{
    Session s(Layout {}, longSequence());
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    const int first = s.seq.firstFrame, start = 12;
    const auto fromStart = referenceFrames(s.seq, { m, true, 1.0, kAllAux, "", 0.0, start });
    const auto single = referenceFrames(s.seq, { m, false, 1.0, kAllAux });
    auto inst = s.instance(m, kAllAux);
    ASSERT_EQ(s.host.setParam(inst.get(), "startFrame", start), kOfxStatOK);
    ASSERT_EQ(s.host.setParam(inst.get(), "useStartFrame", 1), kOfxStatOK);
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 15), fromStart[15 - first]));
    EXPECT_EQ(sourceFetches(inst.get()), range(start, 15));
    EXPECT_EQ(inst->clip("Source")->framesNeeded, (std::vector<double> { 12, 15 }));
    // Before the start frame a frame is denoised on its own; at it the history restarts.
    for (int t : { 10, 11, 12, 13 }) {
        const auto& want = t < start ? single : fromStart;
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t), want[t - first])) << t;
        EXPECT_EQ(sourceFetches(inst.get()), range(t, t)) << t;
    }
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHistory, MixBlendsWithSourceWithoutReplaying)
{
    Session s(Layout { true, 1 });
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    const auto ref = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
    auto inst = s.instance(m, kAllAux);
    const OfxParamStruct* mix = inst->params.find("mix");
    ASSERT_NE(mix, nullptr);
    EXPECT_EQ(mix->props.getDouble(kOfxParamPropDefault), 1.0);
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 4), ref[3]));
    sourceFetches(inst.get());

    ASSERT_EQ(s.host.setParam(inst.get(), "mix", 0.25), kOfxStatOK);
    const std::vector<float> source = s.seq.plane("color", 4, 1.0);
    std::vector<float> want(ref[3].size());
    for (size_t i = 0; i < want.size(); ++i)
        want[i] = 0.25f * ref[3][i] + 0.75f * source[i];
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 4, 1.0, 2), want));
    // Only frame 4's Source tiles were fetched for the blend: the denoised frame came from the
    // cache, no history was replayed.
    EXPECT_EQ(sourceFetches(inst.get()), range(4, 4));

    // Mix 0: the effect is an identity (the host passes Source through).
    ASSERT_EQ(s.host.setParam(inst.get(), "mix", 0.0), kOfxStatOK);
    OfxPropertySetStruct in, out;
    in.setDoubles(kOfxPropTime, { 4.0 });
    in.setDoubles(kOfxImageEffectPropRenderScale, { 1.0, 1.0 });
    in.setInts(kOfxImageEffectPropRenderWindow, { 10, -6, 50, 18 });
    in.setStrings(kOfxImageEffectPropFieldToRender, { kOfxImageFieldNone });
    EXPECT_EQ(s.host.action(kOfxImageEffectActionIsIdentity, inst.get(), &in, &out), kOfxStatOK);
    EXPECT_EQ(out.getString(kOfxPropName), "Source");
    EXPECT_EQ(s.host.liveImages(), 0);
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

// Frames rendered after a jump differ from a sequential render by the history older than the
// window. Measured on this sequence (relative RMS difference over RGB at frame 23, after a jump vs
// the sequential run; the test prints it): within kTolerance with the default window (BMFR, whose
// second accumulation keeps 0.9^n of older frames, differs most), and smaller with a longer one.
// plugin/README.md quotes the figures.
TEST(PluginHistory, TheDefaultWindowStaysCloseToTheSequentialRun)
{
    constexpr double kTolerance = 0.1;
    Session s(Layout {}, longSequence());
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : methodsUnderTest()) {
        SCOPED_TRACE("method " + m);
        const auto sequential = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
        const std::vector<float>& want = sequential[22];
        auto inst = s.instance(m, kAllAux);
        double relative[2] = {};
        for (int k = 0; k < 2; ++k) {
            const int n = k == 0 ? 8 : 16;
            ASSERT_EQ(s.host.setParam(inst.get(), "historyFrames", n), kOfxStatOK);
            const std::vector<float> got = s.render(inst.get(), 23);
            ASSERT_EQ(got.size(), want.size());
            double diff = 0, ref = 0;
            for (size_t i = 0; i < got.size(); ++i) {
                if (i % 4 == 3)
                    continue;
                diff += (double(got[i]) - want[i]) * (double(got[i]) - want[i]);
                ref += double(want[i]) * want[i];
            }
            relative[k] = std::sqrt(diff / ref);
            std::printf("%s: historyFrames %d vs sequential, relative RMS difference %.4f\n",
                m.c_str(), n, relative[k]);
        }
        EXPECT_GT(relative[0], 0.0); // the window is shorter than the history: not the same run
        EXPECT_LT(relative[0], kTolerance);
        EXPECT_LT(relative[1], relative[0]);
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}
