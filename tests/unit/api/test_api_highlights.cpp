// SPDX-License-Identifier: Apache-2.0
// The highlight bypass through the C API (stages/highlight_bypass.h): AFN_STAT_HIGHLIGHTS counts
// the pixels kept unfiltered in the last frame for svgf and bmfr (one bright pixel on a flat
// frame: 1; highlights=0: 0), and is 0, not an error, for a method without the bypass (ta). On
// the flat frame the bright pixel keeps its value in the output within the accumulation's
// rounding and the share of the limit its filter spreads, and its neighbours stay near the flat
// level.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

constexpr int kW = 40, kH = 24, kX = 17, kY = 9;
constexpr float kFlat = 0.3f, kBright = 3000.0f;

struct Result {
    float kept = -1.0f;
    std::vector<float> out;
};

Result run(const char* method, double highlights)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter(method);
    if (highlights >= 0.0)
        filter.set("highlights", static_cast<float>(highlights));
    std::vector<float> color(kW * kH * 3, kFlat), albedo(kW * kH * 3, 1.0f);
    std::vector<float> normal(kW * kH * 3, 0.0f), depth(kW * kH, 2.0f);
    for (int i = 0; i < kW * kH; ++i)
        normal[i * 3 + 2] = 1.0f;
    for (int c = 0; c < 3; ++c)
        color[(kY * kW + kX) * 3 + c] = kBright;
    Result r;
    r.out.assign(kW * kH * 3, 0.0f);
    filter.setImage(AFN_IMAGE_COLOR, color.data(), afn::Format::Float3, kW, kH);
    filter.setImage(AFN_IMAGE_ALBEDO, albedo.data(), afn::Format::Float3, kW, kH);
    filter.setImage(AFN_IMAGE_NORMAL, normal.data(), afn::Format::Float3, kW, kH);
    filter.setImage(AFN_IMAGE_DEPTH, depth.data(), afn::Format::Float, kW, kH);
    filter.setImage(AFN_IMAGE_OUTPUT, r.out.data(), afn::Format::Float3, kW, kH);
    filter.commit();
    filter.execute();
    std::string message;
    EXPECT_EQ(device.getError(&message), afn::Error::None) << message;
    r.kept = filter.get<float>(AFN_STAT_HIGHLIGHTS);
    return r;
}

} // namespace

TEST(ApiHighlights, KeptPixelsAreReportedAndStayPoints)
{
    for (const char* method : { "svgf", "bmfr" }) {
        const Result on = run(method, -1.0), off = run(method, 0.0);
        EXPECT_EQ(on.kept, 1.0f) << method;
        EXPECT_EQ(off.kept, 0.0f) << method;
        const std::size_t i = (kY * kW + kX) * 3;
        // The pixel keeps its value but for what the filter spread of the limit's share (the
        // limit is 4 here: 8 x the flat frame's 0.5 bin).
        EXPECT_NEAR(on.out[i], kBright, 2e-3 * kBright) << method;
        // The right neighbour: near the flat level with the bypass, far from it without.
        const float nearOn = std::fabs(on.out[i + 3] - kFlat);
        const float nearOff = std::fabs(off.out[i + 3] - kFlat);
        EXPECT_LT(nearOn, 0.1f) << method;
        EXPECT_GT(nearOff, 10.0f * nearOn) << method;
    }
    EXPECT_EQ(run("ta", -1.0).kept, 0.0f);
}
