// SPDX-License-Identifier: Apache-2.0
// The "quality" parameter (AFN_PARAM_QUALITY) through the C API: every denoising method lists it
// with the choices fast|balanced|high and default balanced (identity has none), a wrong value is
// an InvalidArgument naming the choices, and afn's three tiers give three results of which
// balanced equals a filter that never set the parameter.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace {

/// The parameter `name` of filter type `type`, or false.
bool findParam(const std::string& type, const char* name, AFNParamInfo& info)
{
    for (int i = 0, n = afnGetFilterTypeNumParams(type.c_str()); i < n; ++i)
        if (afnGetFilterTypeParam(type.c_str(), i, &info) && std::strcmp(info.name, name) == 0)
            return true;
    return false;
}

struct Sequence {
    static constexpr int kW = 24, kH = 14;
    std::vector<float> color, albedo, normal, depth;
    explicit Sequence(int frame)
        : color(kW * kH * 3)
        , albedo(kW * kH * 3, 0.6f)
        , normal(kW * kH * 3)
        , depth(kW * kH)
    {
        for (int i = 0; i < kW * kH; ++i) {
            for (int c = 0; c < 3; ++c)
                color[3 * i + c] = static_cast<float>((i * 7 + c * 3 + frame * 5) % 13) * 0.1f;
            normal[3 * i + 2] = 1.0f;
            depth[i] = 1.0f + 0.01f * static_cast<float>(i % kW);
        }
    }
};

/// afn over three frames with `quality` (empty: not set); the last frame's output.
std::vector<float> runAfn(afn::DeviceRef& device, const std::string& quality)
{
    afn::FilterRef f = device.newFilter("afn");
    if (!quality.empty())
        f.set(AFN_PARAM_QUALITY, quality.c_str());
    std::vector<float> out(Sequence::kW * Sequence::kH * 3);
    for (int frame = 0; frame < 3; ++frame) {
        Sequence s(frame);
        f.setImage(
            AFN_IMAGE_COLOR, s.color.data(), afn::Format::Float3, Sequence::kW, Sequence::kH);
        f.setImage(
            AFN_IMAGE_ALBEDO, s.albedo.data(), afn::Format::Float3, Sequence::kW, Sequence::kH);
        f.setImage(
            AFN_IMAGE_NORMAL, s.normal.data(), afn::Format::Float3, Sequence::kW, Sequence::kH);
        f.setImage(AFN_IMAGE_DEPTH, s.depth.data(), afn::Format::Float, Sequence::kW, Sequence::kH);
        f.setImage(AFN_IMAGE_OUTPUT, out.data(), afn::Format::Float3, Sequence::kW, Sequence::kH);
        f.commit();
        f.execute();
    }
    return out;
}

} // namespace

TEST(ApiQuality, EveryDenoisingMethodListsTheTiers)
{
    for (const std::string& type : afn::filterTypes()) {
        AFNParamInfo info {};
        const bool has = findParam(type, AFN_PARAM_QUALITY, info);
        EXPECT_EQ(has, type != "identity") << type;
        if (!has)
            continue;
        EXPECT_EQ(info.type, AFN_PARAM_STRING) << type;
        EXPECT_STREQ(info.choices, "fast|balanced|high") << type;
        EXPECT_STREQ(info.defaultString, "balanced") << type;
        EXPECT_GT(std::strlen(info.help), 20u) << type;
    }
}

TEST(ApiQuality, WrongTierIsAnError)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef f = device.newFilter("svgf");
    f.set(AFN_PARAM_QUALITY, "high");
    EXPECT_EQ(device.getError(), afn::Error::None);
    EXPECT_EQ(f.get<std::string>(AFN_PARAM_QUALITY), "high");
    f.set(AFN_PARAM_QUALITY, "ultra");
    std::string msg;
    EXPECT_EQ(device.getError(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("fast|balanced|high"), std::string::npos) << msg;
    EXPECT_EQ(f.get<std::string>(AFN_PARAM_QUALITY), "high") << "a rejected value changes nothing";
}

TEST(ApiQuality, AfnTiersAreThreeResultsAndBalancedIsTheDefault)
{
    if (!afn::isFilterTypeReady("afn"))
        GTEST_SKIP() << "this build has no built-in afn weights";
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    const std::vector<float> plain = runAfn(device, "");
    const std::vector<float> balanced = runAfn(device, "balanced");
    const std::vector<float> fast = runAfn(device, "fast");
    const std::vector<float> high = runAfn(device, "high");
    EXPECT_EQ(device.getError(), afn::Error::None);
    EXPECT_EQ(balanced, plain);
    EXPECT_NE(fast, plain);
    EXPECT_NE(high, plain);
    EXPECT_NE(high, fast);
}
