// SPDX-License-Identifier: Apache-2.0
// The "quality" parameter in the OFX plugin: every denoising method has its own choice
// <method>_quality (fast, balanced, high; default balanced; the help says what the tiers do for
// that method), and afn rendered with fast or high equals the C API filter with that tier, while
// differing from balanced.
#include "plugin_session.h"

#include <afn/afn.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace ofxhost;
using namespace ofxtest;

TEST(PluginQuality, EveryDenoisingMethodHasItsOwnQualityChoice)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    for (const std::string& m : methodsUnderTest()) {
        if (m == "identity")
            continue;
        const OfxParamStruct* p = s.general->params.find(m + "_quality");
        ASSERT_NE(p, nullptr) << m;
        EXPECT_EQ(p->props.getStrings(kOfxParamPropChoiceOption),
            (std::vector<std::string> { "fast", "balanced", "high" }))
            << m;
        EXPECT_EQ(p->props.getInt(kOfxParamPropDefault), 1) << m << ": balanced";
        EXPECT_FALSE(p->props.getStrings(kOfxParamPropHint).empty()) << m;
    }
}

TEST(PluginQuality, AfnTiersMatchTheCApi)
{
    const std::vector<std::string> methods = methodsUnderTest();
    if (std::find(methods.begin(), methods.end(), "afn") == methods.end())
        GTEST_SKIP() << "afn is not in this build's methods";
    Session s;
    ASSERT_TRUE(s.loaded);
    ReferenceOptions balancedOpt { "afn", true, 1.0, kAllAux };
    const auto balanced = referenceFrames(s.seq, balancedOpt);
    const char* tiers[] = { "fast", "balanced", "high" };
    for (int index : { 0, 2 }) {
        SCOPED_TRACE(tiers[index]);
        auto inst = s.instance("afn", kAllAux);
        ASSERT_EQ(s.host.setParam(inst.get(), "afn_quality", index), kOfxStatOK);
        ReferenceOptions opt = balancedOpt;
        opt.stringParam = AFN_PARAM_QUALITY;
        opt.stringValue = tiers[index];
        const auto ref = referenceFrames(s.seq, opt);
        for (int k = 0; k < s.seq.numFrames; ++k) {
            const std::vector<float> got = s.render(inst.get(), s.seq.firstFrame + k);
            EXPECT_TRUE(nearlyEqual(got, ref[k])) << "frame " << k;
            EXPECT_FALSE(nearlyEqual(got, balanced[k])) << "frame " << k;
        }
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}
