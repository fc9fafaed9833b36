// SPDX-License-Identifier: Apache-2.0
// The OFX plugin driven through the in-process test host, compared with the same filter run
// directly through the C API over the same frames (whole frames, tiles, render scale 0.5,
// out-of-order times, two threads), plus describe contracts, identity, abort, errors and the
// device choice.
#include "plugin_session.h"

#include <afn/afn.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>

using namespace ofxhost;
using namespace ofxtest;

TEST(PluginHost, LoadsDescribesAndUnloads)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const OfxPlugin* p = s.host.plugin();
    EXPECT_EQ(s.host.numPlugins(), 1);
    EXPECT_STREQ(p->pluginApi, "OfxImageEffectPluginAPI");
    EXPECT_EQ(p->apiVersion, 1);
    EXPECT_STREQ(p->pluginIdentifier, "org.afn.Denoise");
    EXPECT_EQ(p->pluginVersionMajor, 1u);
    EXPECT_EQ(p->pluginVersionMinor, 1u);
    ASSERT_NE(p->setHost, nullptr);
    ASSERT_NE(p->mainEntry, nullptr);

    const OfxPropertySetStruct& d = s.host.descriptor()->props;
    EXPECT_EQ(d.getStrings(kOfxImageEffectPropSupportedContexts).size(), 2u);
    EXPECT_EQ(d.getString(kOfxImageEffectPropSupportedPixelDepths), kOfxBitDepthFloat);
    EXPECT_EQ(d.getInt(kOfxImageEffectPropSupportsTiles), 1);
    EXPECT_EQ(d.getInt(kOfxImageEffectPropTemporalClipAccess), 1);
    EXPECT_EQ(d.getString(kOfxImageEffectPluginRenderThreadSafety), kOfxImageEffectRenderFullySafe);

    // Clips: General has the four optional auxiliary clips, Filter only Source and Output.
    for (const char* c : { "Source", "Output" }) {
        ASSERT_NE(s.general->clip(c), nullptr) << c;
        ASSERT_NE(s.filter->clip(c), nullptr) << c;
    }
    for (const char* c : kClipOf) {
        ASSERT_NE(s.general->clip(c), nullptr) << c;
        EXPECT_EQ(s.general->clip(c)->props.getInt(kOfxImageClipPropOptional), 1) << c;
        EXPECT_EQ(s.filter->clip(c), nullptr) << c;
    }
    EXPECT_EQ(s.filter->clips.size(), 2u);

    // Parameters: the method choice lists the library's methods (each label starts with the id);
    // every library parameter except the two the plugin sets itself appears with the library's
    // default.
    const OfxParamStruct* method = s.general->params.find("method");
    ASSERT_NE(method, nullptr);
    const auto& labels = method->props.getStrings(kOfxParamPropChoiceOption);
    ASSERT_EQ(labels.size(), afn::filterTypes().size());
    for (size_t i = 0; i < labels.size(); ++i) {
        std::string id = labels[i].substr(0, labels[i].find(' '));
        std::transform(id.begin(), id.end(), id.begin(), ::tolower);
        EXPECT_EQ(id, afn::filterTypes()[i]) << labels[i];
    }
    EXPECT_EQ(s.general->params.find("temporal")->props.getInt(kOfxParamPropDefault), 1);
    EXPECT_EQ(s.filter->params.find("temporal")->props.getInt(kOfxParamPropDefault), 0);
    for (const std::string& m : afn::filterTypes())
        for (const AFNParamInfo& info : afn::filterTypeParams(m.c_str())) {
            const std::string n = info.name;
            if (n == "motion.yUp" || n == "motion.scale")
                continue;
            const OfxParamStruct* p = s.general->params.find(ofxName(*s.general, m, n));
            ASSERT_NE(p, nullptr) << m << " " << n;
            EXPECT_EQ(p->props.getInt(kOfxParamPropAnimates), 0);
            if (info.type == AFN_PARAM_FLOAT) {
                EXPECT_EQ(p->type, kOfxParamTypeDouble);
                EXPECT_EQ(p->props.getDouble(kOfxParamPropDefault), info.defaultValue) << n;
            } else if (info.type == AFN_PARAM_STRING) {
                EXPECT_EQ(p->type, kOfxParamTypeChoice);
                const auto& options = p->props.getStrings(kOfxParamPropChoiceOption);
                EXPECT_EQ(options.at(p->props.getInt(kOfxParamPropDefault)), info.defaultString);
            } else {
                EXPECT_EQ(p->props.getInt(kOfxParamPropDefault), int(info.defaultValue)) << n;
            }
        }
}

TEST(PluginHost, OnlyTheCurrentMethodsParametersAreShown)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : afn::filterTypes()) {
        auto inst = s.instance(m, {});
        int groups = 0;
        for (const auto& p : inst->params.params) {
            if (p->name.rfind("group_", 0) != 0 || p->name == "group_inputs"
                || p->name == "group_history")
                continue;
            ++groups;
            const std::string owner = p->name.substr(6);
            EXPECT_EQ(p->props.getInt(kOfxParamPropSecret), owner == m ? 0 : 1)
                << m << " " << p->name;
        }
        if (afn::filterTypes().size() > 2)
            EXPECT_GT(groups, 1); // methods with own parameters
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginHost, WholeFramesMatchCApi)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : methodsUnderTest()) {
        SCOPED_TRACE("method " + m);
        auto inst = s.instance(m, kAllAux);
        const auto ref = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
        for (int k = 0; k < s.seq.numFrames; ++k) {
            const double t = s.seq.firstFrame + k;
            EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t), ref[k])) << "frame " << t;
            const OfxImageClipStruct* src = inst->clip("Source");
            if (m != "identity") {
                EXPECT_EQ(src->framesNeeded, (std::vector<double> { double(s.seq.firstFrame), t }));
                EXPECT_EQ(src->lastRoI, (std::vector<double> { 10, -6, 50, 18 })); // whole RoD
            }
        }
        EXPECT_EQ(s.host.liveImages(), 0);
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginHost, StitchedTilesWithNegativeRowBytesMatchCApi)
{
    Session s(Layout { true, 3 });
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : methodsUnderTest()) {
        SCOPED_TRACE("method " + m);
        auto inst = s.instance(m, kAllAux);
        const auto ref = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
        for (int k = 0; k < s.seq.numFrames; ++k)
            EXPECT_TRUE(nearlyEqual(s.render(inst.get(), s.seq.firstFrame + k, 1.0, 3), ref[k]))
                << "frame " << k;
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginHost, RenderScaleHalfMatchesCApiAtHalfResolution)
{
    Session s(Layout { false, 2 });
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : methodsUnderTest()) {
        SCOPED_TRACE("method " + m);
        auto inst = s.instance(m, kAllAux);
        const auto ref = referenceFrames(s.seq, { m, true, 0.5, kAllAux });
        for (int k = 0; k < s.seq.numFrames; ++k)
            EXPECT_TRUE(nearlyEqual(s.render(inst.get(), s.seq.firstFrame + k, 0.5, 2), ref[k]))
                << "frame " << k;
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginHost, OutOfOrderRequestsMatchSequentialResults)
{
    Session s(Layout { true, 0 });
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    auto inst = s.instance(m, kAllAux);
    const auto ref = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
    for (int t : { 4, 2, 6, 1, 3, 5, 5, 6, 2 })
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t, 1.0, 2), ref[t - s.seq.firstFrame]))
            << "frame " << t;

    // A parameter change invalidates the history: results follow the new value, and going back
    // restores the old results.
    for (const AFNParamInfo& info : afn::filterTypeParams(m.c_str())) {
        if (info.type != AFN_PARAM_FLOAT || std::strncmp(info.name, "motion.", 7) == 0)
            continue;
        const double v = info.defaultValue != info.minValue
            ? 0.5 * (info.defaultValue + info.minValue)
            : 0.5 * (info.defaultValue + info.maxValue);
        const std::string name = ofxName(*s.general, m, info.name);
        ASSERT_EQ(s.host.setParam(inst.get(), name, v), kOfxStatOK);
        const auto changed = referenceFrames(s.seq, { m, true, 1.0, kAllAux, info.name, v });
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 3), changed[3 - s.seq.firstFrame])) << name;
        ASSERT_EQ(s.host.setParam(inst.get(), name, info.defaultValue), kOfxStatOK);
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 3), ref[3 - s.seq.firstFrame])) << name;
        break;
    }
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHost, TwoThreadsRenderInstancesAndFramesConcurrently)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    auto a = s.instance(m, kAllAux);
    auto b = s.instance(m, kAllAux);
    auto shared = s.instance(m, kAllAux);
    const auto ref = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
    const int n = s.seq.numFrames, first = s.seq.firstFrame;
    std::vector<std::vector<float>> gotA(n), gotB(n), gotShared(n);
    std::thread t1([&] {
        for (int k = 0; k < n; ++k) {
            gotA[k] = s.render(a.get(), first + k, 1.0, 2);
            if (k % 2 == 0)
                gotShared[k] = s.render(shared.get(), first + k);
        }
    });
    std::thread t2([&] {
        for (int k = n - 1; k >= 0; --k) {
            gotB[k] = s.render(b.get(), first + k);
            if (k % 2 == 1)
                gotShared[k] = s.render(shared.get(), first + k, 1.0, 2);
        }
    });
    t1.join();
    t2.join();
    for (int k = 0; k < n; ++k) {
        EXPECT_TRUE(nearlyEqual(gotA[k], ref[k])) << "instance A frame " << k;
        EXPECT_TRUE(nearlyEqual(gotB[k], ref[k])) << "instance B frame " << k;
        EXPECT_TRUE(nearlyEqual(gotShared[k], ref[k])) << "shared instance frame " << k;
    }
    for (auto* i : { a.get(), b.get(), shared.get() })
        EXPECT_EQ(s.host.destroyInstance(i), kOfxStatOK);
}

TEST(PluginHost, FilterContextIsSingleFrameUnlessTemporalIsOn)
{
    Session s(Layout { true, 1 });
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    auto inst = s.instance(m, {}, false);
    const auto single = referenceFrames(s.seq, { m, false, 1.0, {} });
    for (int t : { 3, 1, 6 })
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t), single[t - s.seq.firstFrame])) << t;
    ASSERT_EQ(s.host.setParam(inst.get(), "temporal", 1), kOfxStatOK);
    const auto temporal = referenceFrames(s.seq, { m, true, 1.0, {} });
    for (int t : { 5, 2, 3 })
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t), temporal[t - s.seq.firstFrame])) << t;
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHost, UnconnectedOptionalClipsAreNotBound)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    const std::vector<std::string> aux = { "albedo", "normal" };
    auto inst = s.instance(m, aux);
    const auto ref = referenceFrames(s.seq, { m, true, 1.0, aux });
    for (int t : { 2, 4 })
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t), ref[t - 1])) << t;
    EXPECT_TRUE(inst->clip("Motion")->framesNeeded.empty()); // not asked for
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHost, IsIdentityOnlyForTheIdentityMethod)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : afn::filterTypes()) {
        auto inst = s.instance(m, kAllAux);
        OfxPropertySetStruct in, out;
        in.setDoubles(kOfxPropTime, { 3.0 });
        in.setDoubles(kOfxImageEffectPropRenderScale, { 1.0, 1.0 });
        in.setInts(kOfxImageEffectPropRenderWindow, { 10, -6, 50, 18 });
        in.setStrings(kOfxImageEffectPropFieldToRender, { kOfxImageFieldNone });
        const OfxStatus st = s.host.action(kOfxImageEffectActionIsIdentity, inst.get(), &in, &out);
        if (m == "identity") {
            EXPECT_EQ(st, kOfxStatOK);
            EXPECT_EQ(out.getString(kOfxPropName), "Source");
            EXPECT_EQ(out.getDouble(kOfxPropTime), 3.0);
        } else {
            EXPECT_EQ(st, kOfxStatReplyDefault) << m;
        }
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginHost, AbortStopsARenderAndLeavesNoBadState)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const std::string m = methodsUnderTest().front();
    auto inst = s.instance(m, kAllAux);
    const auto ref = referenceFrames(s.seq, { m, true, 1.0, kAllAux });
    s.host.abortFlag = true;
    Frame f;
    EXPECT_NE(s.host.renderFrame(inst.get(), 4, 1.0, 1, f), kOfxStatOK);
    s.host.abortFlag = false;
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 4), ref[3]));
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), 5), ref[4]));
    EXPECT_EQ(s.host.liveImages(), 0);
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHost, BadInputIsReportedThroughTheMessageSuite)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    ClipSource oneChannel = s.sources["depth"]; // a single-channel image on the Motion clip
    const std::string m = methodsUnderTest().front();
    OfxStatus st = kOfxStatFailed;
    auto inst = s.host.createInstance(*s.general, kOfxImageEffectContextGeneral,
        { { "Source", &s.sources["color"] }, { "Motion", &oneChannel } }, &st);
    ASSERT_EQ(st, kOfxStatOK);
    ASSERT_EQ(s.host.setParam(inst.get(), "method", methodIndex(m)), kOfxStatOK);
    Frame f;
    EXPECT_NE(s.host.renderFrame(inst.get(), 2, 1.0, 1, f), kOfxStatOK);
    const auto messages = s.host.messages();
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages.back().find("motion"), std::string::npos) << messages.back();
    EXPECT_EQ(s.host.liveImages(), 0);
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}

TEST(PluginHost, DeviceChoiceFallsBackToTheCpuWithANote)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const bool hasCuda = static_cast<bool>(afn::newDevice(afn::DeviceType::CUDA));
    const auto ref = referenceFrames(s.seq, { "ta", true, 1.0, kAllAux });
    // auto: ta runs on the CPU only, so the CPU is used, with a note in the host's log saying why.
    auto inst = s.instance("ta", kAllAux);
    ASSERT_EQ(s.host.setParam(inst.get(), "device", 2), kOfxStatOK);
    for (int k = 0; k < s.seq.numFrames; ++k)
        EXPECT_TRUE(nearlyEqual(s.render(inst.get(), s.seq.firstFrame + k), ref[k])) << k;
    auto messages = s.host.messages();
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_EQ(messages[0].rfind(kOfxMessageLog, 0), 0u) << messages[0];
    EXPECT_NE(
        messages[0].find(hasCuda ? "runs on the CPU only" : "no CUDA device"), std::string::npos)
        << messages[0];
    // cuda: an error without a CUDA device; with one, ta does not run there.
    ASSERT_EQ(s.host.setParam(inst.get(), "device", 1), kOfxStatOK);
    Frame f;
    EXPECT_NE(s.host.renderFrame(inst.get(), s.seq.firstFrame, 1.0, 1, f), kOfxStatOK);
    messages = s.host.messages();
    ASSERT_EQ(messages.size(), 2u);
    EXPECT_NE(messages[1].find(hasCuda ? "does not run on the cuda device" : "device cuda: "),
        std::string::npos)
        << messages[1];
    // cpu again: the reference results, no further message.
    ASSERT_EQ(s.host.setParam(inst.get(), "device", 0), kOfxStatOK);
    EXPECT_TRUE(nearlyEqual(s.render(inst.get(), s.seq.firstFrame + 2), ref[2]));
    EXPECT_EQ(s.host.messages().size(), 2u);
    EXPECT_EQ(s.host.liveImages(), 0);
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}
