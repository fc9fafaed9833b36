// SPDX-License-Identifier: Apache-2.0
// Saved compositing projects refer to OFX parameters by name and to choices by index: the names,
// types and choice option ids of both contexts are pinned against tests/plugin/ofx_params.golden.
// An option's id is the first word of its label, lower-cased ("SVGF (spatiotemporal ...)" ->
// svgf): labels may become more readable, ids and their order never change. A difference fails
// with the whole current list; regenerate the golden file only to append new parameters, or for a
// change that bumps the plugin's major version (AFN_UPDATE_GOLDEN=1 writes it).
#include "ofx_test_host.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace ofxhost;

namespace {

std::string optionId(const std::string& label)
{
    std::string id = label.substr(0, label.find(' '));
    std::transform(
        id.begin(), id.end(), id.begin(), [](unsigned char c) { return std::tolower(c); });
    return id;
}

std::string describeParams(const std::string& context, const OfxImageEffectStruct& effect)
{
    std::ostringstream os;
    for (const auto& p : effect.params.params) {
        os << context << ' ' << p->name << ' ' << p->type;
        if (p->props.has(kOfxParamPropChoiceOption))
            for (const std::string& o : p->props.getStrings(kOfxParamPropChoiceOption))
                os << ' ' << optionId(o);
        os << '\n';
    }
    return os.str();
}

std::string readFile(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

} // namespace

TEST(PluginParamNames, MatchTheGoldenList)
{
    Host host;
    std::string error;
    ASSERT_TRUE(host.load(AFN_OFX_BINARY, &error)) << error;
    ASSERT_EQ(host.describe(), kOfxStatOK);
    std::unique_ptr<OfxImageEffectStruct> general, filter;
    ASSERT_EQ(host.describeInContext(kOfxImageEffectContextGeneral, general), kOfxStatOK);
    ASSERT_EQ(host.describeInContext(kOfxImageEffectContextFilter, filter), kOfxStatOK);
    const std::string current
        = describeParams("general", *general) + describeParams("filter", *filter);
    EXPECT_EQ(host.unload(), kOfxStatOK);

    const std::string golden = AFN_OFX_PARAMS_GOLDEN;
    if (std::getenv("AFN_UPDATE_GOLDEN")) {
        std::ofstream(golden) << current;
        GTEST_SKIP() << "wrote " << golden;
    }
    EXPECT_EQ(current, readFile(golden)) << "OFX parameters changed; saved projects would break";
}
