// SPDX-License-Identifier: Apache-2.0
// How the effect presents itself in a host: menu grouping, readable choice labels over stable ids,
// slider display ranges inside the accepted ranges, parameters hidden where they cannot act (the
// Filter context has no auxiliary inputs) and history controls enabled only where they act.
#include "plugin_session.h"

#include <afn/afn.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>

using namespace ofxhost;
using namespace ofxtest;

namespace {

std::string firstWordLower(const std::string& label)
{
    std::string id = label.substr(0, label.find(' '));
    std::transform(
        id.begin(), id.end(), id.begin(), [](unsigned char c) { return std::tolower(c); });
    return id;
}

int secret(const OfxImageEffectStruct& inst, const std::string& name)
{
    const OfxParamStruct* p = inst.params.find(name);
    EXPECT_NE(p, nullptr) << name;
    return p && p->props.has(kOfxParamPropSecret) ? p->props.getInt(kOfxParamPropSecret) : 0;
}

int enabled(const OfxImageEffectStruct& inst, const std::string& name)
{
    const OfxParamStruct* p = inst.params.find(name);
    EXPECT_NE(p, nullptr) << name;
    return p && p->props.has(kOfxParamPropEnabled) ? p->props.getInt(kOfxParamPropEnabled) : 1;
}

// Library parameters that only act through auxiliary inputs (see plugin/param_display.cpp).
bool auxOnly(const std::string& name)
{
    for (const char* n : { "positionLimit", "positionLimitSquared", "normalLimitSquared",
             "depthLimit", "aux", "sigmaN", "sigmaZ" })
        if (name == n)
            return true;
    return false;
}

} // namespace

TEST(PluginPresentation, FiledUnderFilterDenoiseWithReadableChoiceLabels)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    const OfxPropertySetStruct& d = s.host.descriptor()->props;
    EXPECT_EQ(d.getString(kOfxImageEffectPluginPropGrouping), "Filter/Denoise");
    EXPECT_EQ(d.getString(kOfxPropLabel), "afn Denoise");
    // Options are "ID (what it is)": the first word is the id saved projects rely on (by index),
    // the rest says what the method is.
    const auto& methods
        = s.general->params.find("method")->props.getStrings(kOfxParamPropChoiceOption);
    ASSERT_EQ(methods.size(), afn::filterTypes().size());
    for (size_t i = 0; i < methods.size(); ++i) {
        EXPECT_EQ(firstWordLower(methods[i]), afn::filterTypes()[i]) << methods[i];
        EXPECT_NE(methods[i].find(" ("), std::string::npos) << methods[i];
    }
    if (const int afn = methodIndex("afn"); afn < int(methods.size()))
        EXPECT_EQ(methods[afn], "AFN (adaptive fusion network)");
    const auto& devices
        = s.general->params.find("device")->props.getStrings(kOfxParamPropChoiceOption);
    ASSERT_EQ(devices.size(), 3u);
    EXPECT_EQ(devices[0], "CPU");
    EXPECT_EQ(firstWordLower(devices[1]), "cuda");
    EXPECT_EQ(firstWordLower(devices[2]), "auto");
}

TEST(PluginPresentation, SlidersShowAUsefulPartOfTheAcceptedRange)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    int narrowed = 0;
    for (const auto& p : s.general->params.params) {
        const bool isDouble = p->type == kOfxParamTypeDouble;
        if ((!isDouble && p->type != kOfxParamTypeInteger) || !p->props.has(kOfxParamPropMin)
            || !p->props.has(kOfxParamPropDisplayMin))
            continue;
        auto get = [&](const char* prop) {
            return isDouble ? p->props.getDouble(prop) : double(p->props.getInt(prop));
        };
        const double lo = get(kOfxParamPropMin), hi = get(kOfxParamPropMax),
                     dlo = get(kOfxParamPropDisplayMin), dhi = get(kOfxParamPropDisplayMax),
                     def = get(kOfxParamPropDefault);
        SCOPED_TRACE(p->name);
        EXPECT_LE(lo, dlo);
        EXPECT_LT(dlo, dhi);
        EXPECT_LE(dhi, hi);
        EXPECT_LE(dlo, def);
        EXPECT_LE(def, dhi);
        // A range reaching far beyond the default is shown around it.
        if (def > 0 && hi > 10 * def) {
            EXPECT_LE(dhi, 4 * def);
            ++narrowed;
        }
    }
    EXPECT_GT(narrowed, 0);
    if (const OfxParamStruct* sigmaL = s.general->params.find("svgf_sigmaL")) {
        EXPECT_EQ(sigmaL->props.getDouble(kOfxParamPropDisplayMin), 0.0);
        EXPECT_EQ(sigmaL->props.getDouble(kOfxParamPropDisplayMax), 16.0);
        EXPECT_EQ(sigmaL->props.getDouble(kOfxParamPropMax), 1000.0);
    }
}

TEST(PluginPresentation, FilterContextHidesWhatNeedsAuxiliaryInputs)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    for (bool general : { true, false })
        for (const std::string& m : afn::filterTypes()) {
            SCOPED_TRACE(std::string(general ? "general " : "filter ") + m);
            auto inst = s.instance(m, {}, general);
            EXPECT_EQ(secret(*inst, "group_inputs"), general ? 0 : 1);
            for (const AFNParamInfo& info : afn::filterTypeParams(m.c_str())) {
                const std::string n = info.name;
                if (n == "motion.yUp" || n == "motion.scale")
                    continue;
                const std::string name = ofxName(*inst, m, n);
                const bool shared = name.find(m + "_") != 0;
                const bool hidden = !general && (shared || auxOnly(n));
                EXPECT_EQ(secret(*inst, name), hidden ? 1 : 0) << name;
            }
            // Always shown: the method, the history controls, the mix.
            for (const char* n : { "method", "temporal", "historyFrames", "mix" })
                EXPECT_EQ(secret(*inst, n), 0) << n;
            EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
        }
    // The descriptor already hides them (hosts may build the panel from it).
    EXPECT_EQ(s.filter->params.find("group_inputs")->props.getInt(kOfxParamPropSecret), 1);
}

TEST(PluginPresentation, HistoryControlsAreEnabledWhereTheyAct)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    auto inst = s.instance(methodsUnderTest().front(), {}, false); // Filter: temporal off
    EXPECT_EQ(enabled(*inst, "historyFrames"), 0);
    EXPECT_EQ(enabled(*inst, "useStartFrame"), 0);
    EXPECT_EQ(enabled(*inst, "startFrame"), 0);
    ASSERT_EQ(s.host.setParam(inst.get(), "temporal", 1), kOfxStatOK);
    EXPECT_EQ(enabled(*inst, "historyFrames"), 1);
    EXPECT_EQ(enabled(*inst, "useStartFrame"), 1);
    EXPECT_EQ(enabled(*inst, "startFrame"), 0);
    ASSERT_EQ(s.host.setParam(inst.get(), "useStartFrame", 1), kOfxStatOK);
    EXPECT_EQ(enabled(*inst, "startFrame"), 1);
    const OfxParamStruct* frames = inst->params.find("historyFrames");
    EXPECT_EQ(frames->props.getInt(kOfxParamPropDefault), 8);
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}
