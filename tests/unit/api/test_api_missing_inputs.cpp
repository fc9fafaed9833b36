// SPDX-License-Identifier: Apache-2.0
// AFN_STAT_MISSING_INPUTS: after an execute, the inputs the method reads that the frame lacked.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

constexpr int kW = 16, kH = 12;

/// Run one frame of `method` with colour plus the named inputs; the missing-inputs text.
std::string missingAfterOneFrame(const char* method, const std::vector<const char*>& inputs)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter(method);
    std::vector<float> color(kW * kH * 3, 0.5f), out(kW * kH * 3), one(kW * kH, 1.0f);
    std::vector<float> three(kW * kH * 3, 0.0f), two(kW * kH * 2, 0.0f);
    for (int i = 0; i < kW * kH; ++i)
        three[i * 3 + 2] = 1.0f; // unit normals
    filter.setImage(AFN_IMAGE_COLOR, color.data(), afn::Format::Float3, kW, kH);
    filter.setImage(AFN_IMAGE_OUTPUT, out.data(), afn::Format::Float3, kW, kH);
    for (const char* name : inputs) {
        const std::string n = name;
        if (n == AFN_IMAGE_DEPTH)
            filter.setImage(name, one.data(), afn::Format::Float, kW, kH);
        else if (n == AFN_IMAGE_MOTION)
            filter.setImage(name, two.data(), afn::Format::Float2, kW, kH);
        else
            filter.setImage(name, three.data(), afn::Format::Float3, kW, kH);
    }
    filter.commit();
    filter.execute();
    std::string message;
    EXPECT_EQ(device.getError(&message), afn::Error::None) << message;
    return filter.get<std::string>(AFN_STAT_MISSING_INPUTS);
}

} // namespace

TEST(ApiMissingInputs, ColourOnlyNamesWhatSvgfUses)
{
    const std::string m = missingAfterOneFrame("svgf", {});
    EXPECT_NE(m.find("albedo (demodulation"), std::string::npos) << m;
    EXPECT_NE(m.find("normal (edge-stopping)"), std::string::npos) << m;
    EXPECT_NE(m.find("depth or position with a camera (edge-stopping)"), std::string::npos) << m;
    EXPECT_NE(m.find("motion or position with a camera (reprojection"), std::string::npos) << m;
}

TEST(ApiMissingInputs, NothingMissingWithEveryInput)
{
    const std::vector<const char*> all
        = { AFN_IMAGE_ALBEDO, AFN_IMAGE_NORMAL, AFN_IMAGE_DEPTH, AFN_IMAGE_MOTION };
    for (const char* method : { "ta", "svgf", "bmfr" })
        EXPECT_EQ(missingAfterOneFrame(method, all), "") << method;
    EXPECT_EQ(missingAfterOneFrame("identity", {}), "") << "identity reads no AOVs";
    // bmfr takes depth when there is no position.
    const std::string m = missingAfterOneFrame("bmfr", { AFN_IMAGE_ALBEDO, AFN_IMAGE_DEPTH });
    EXPECT_EQ(m.find("position or depth"), std::string::npos) << m;
    EXPECT_NE(m.find("normal (regression features)"), std::string::npos) << m;
}
