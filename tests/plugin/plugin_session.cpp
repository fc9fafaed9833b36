// SPDX-License-Identifier: Apache-2.0
#include "plugin_session.h"

#include <afn/afn.hpp>

#include <algorithm>
#include <cmath>

using namespace ofxhost;

namespace ofxtest {

const std::vector<std::string> kAllAux = { "albedo", "normal", "depth", "position", "motion" };
const char* const kClipOf[5] = { "Albedo", "Normal", "Depth", "Position", "Motion" };

std::vector<std::string> methodsUnderTest()
{
    std::vector<std::string> out;
    for (const std::string& m : afn::filterTypes())
        if (m != "identity")
            out.push_back(m);
    if (out.empty())
        out.push_back("identity");
    return out;
}

int methodIndex(const std::string& m)
{
    const std::vector<std::string> all = afn::filterTypes();
    return int(std::find(all.begin(), all.end(), m) - all.begin());
}

::testing::AssertionResult nearlyEqual(
    const std::vector<float>& got, const std::vector<float>& want)
{
    if (got.size() != want.size())
        return ::testing::AssertionFailure() << "size " << got.size() << " vs " << want.size();
    for (size_t i = 0; i < got.size(); ++i) {
        const double tol = 1e-5 * std::max(std::abs(double(want[i])), 1e-3);
        if (!(std::abs(double(got[i]) - want[i]) <= tol))
            return ::testing::AssertionFailure()
                << "value " << i << " (pixel " << i / 4 << ", channel " << i % 4 << "): plugin "
                << got[i] << " vs C API " << want[i];
    }
    return ::testing::AssertionSuccess();
}

std::string ofxName(const OfxImageEffectStruct& desc, const std::string& method, std::string name)
{
    std::replace(name.begin(), name.end(), '.', '_');
    return desc.params.find(method + "_" + name) ? method + "_" + name : name;
}

Session::Session(Layout layout, Sequence sequence)
    : host(layout)
    , seq(sequence)
{
    std::string error;
    loaded = host.load(AFN_OFX_BINARY, &error);
    EXPECT_TRUE(loaded) << error;
    if (!loaded)
        return;
    EXPECT_EQ(host.describe(), kOfxStatOK);
    EXPECT_EQ(host.describeInContext(kOfxImageEffectContextGeneral, general), kOfxStatOK);
    EXPECT_EQ(host.describeInContext(kOfxImageEffectContextFilter, filter), kOfxStatOK);
    for (const char* role : { "color", "albedo", "normal", "depth", "position", "motion" })
        sources[role] = seq.source(role);
}

Session::~Session()
{
    if (loaded)
        EXPECT_EQ(host.unload(), kOfxStatOK);
}

std::unique_ptr<OfxImageEffectStruct> Session::instance(
    const std::string& method, const std::vector<std::string>& aux, bool inGeneral)
{
    std::map<std::string, const ClipSource*> inputs = { { "Source", &sources["color"] } };
    for (const std::string& role : aux)
        for (size_t i = 0; i < kAllAux.size(); ++i)
            if (kAllAux[i] == role)
                inputs[kClipOf[i]] = &sources[role];
    OfxStatus s = kOfxStatFailed;
    auto inst = host.createInstance(inGeneral ? *general : *filter,
        inGeneral ? kOfxImageEffectContextGeneral : kOfxImageEffectContextFilter, inputs, &s);
    EXPECT_EQ(s, kOfxStatOK);
    EXPECT_EQ(host.setParam(inst.get(), "method", methodIndex(method)), kOfxStatOK);
    if (const std::string w = testWeightsFor(method); !w.empty())
        EXPECT_EQ(host.setParam(inst.get(), "weights", w), kOfxStatOK);
    return inst;
}

std::vector<float> Session::render(OfxImageEffectStruct* inst, double t, double scale, int tiles)
{
    Frame f;
    const OfxStatus s = host.renderFrame(inst, t, scale, tiles, f);
    EXPECT_EQ(s, kOfxStatOK) << "time " << t;
    return f.rgba;
}

} // namespace ofxtest
