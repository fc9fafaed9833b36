// SPDX-License-Identifier: Apache-2.0
// The aux prefilter's statistics through the C API: after each frame of a history decided clean
// (aux=clean), whose speckle shares the library measures only when asked for, stats.*Speckle are
// that frame's shares, the ones afnEstimateAuxNoise gives for the same buffers; the decision
// stats do not depend on when the shares are asked for.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

constexpr int kW = 40, kH = 24;

/// An albedo of 0.5 with `every`-th pixel 0.05 (isolated: speckle).
std::vector<float> speckledAlbedo(int every)
{
    std::vector<float> a(kW * kH * 3, 0.5f);
    for (int i = 0; i < kW * kH; i += every)
        for (int c = 0; c < 3; ++c)
            a[i * 3 + c] = 0.05f;
    return a;
}

double estimate(afn::DeviceRef& device, const char* role, const std::vector<float>& v, int ch)
{
    AFNAuxNoise n {};
    EXPECT_TRUE(afnEstimateAuxNoise(device.getHandle(), role, v.data(), kW, kH, ch, &n));
    return n.speckle;
}

} // namespace

TEST(ApiAuxStats, EachFramesSpeckleSharesOfACleanHistory)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    for (const char* method : { "ta", "svgf" }) {
        afn::FilterRef filter = device.newFilter(method);
        filter.set(AFN_PARAM_AUX, "clean");
        std::vector<float> color(kW * kH * 3, 0.3f), out(kW * kH * 3);
        std::vector<float> normal(kW * kH * 3, 0.0f), depth(kW * kH, 2.0f);
        for (int i = 0; i < kW * kH; ++i)
            normal[i * 3 + 2] = 1.0f;
        for (int frame = 0; frame < 4; ++frame) {
            std::vector<float> albedo = speckledAlbedo(7 + 4 * frame); // fewer each frame
            std::vector<float> d = depth;
            for (int i = frame; i < kW * kH; i += 13 + frame)
                d[i] = 5.0f; // depth speckle that moves
            filter.setImage(AFN_IMAGE_COLOR, color.data(), afn::Format::Float3, kW, kH);
            filter.setImage(AFN_IMAGE_ALBEDO, albedo.data(), afn::Format::Float3, kW, kH);
            filter.setImage(AFN_IMAGE_NORMAL, normal.data(), afn::Format::Float3, kW, kH);
            filter.setImage(AFN_IMAGE_DEPTH, d.data(), afn::Format::Float, kW, kH);
            filter.setImage(AFN_IMAGE_OUTPUT, out.data(), afn::Format::Float3, kW, kH);
            filter.commit();
            filter.execute();
            std::string message;
            ASSERT_EQ(device.getError(&message), afn::Error::None) << message;
            EXPECT_FALSE(filter.get<bool>(AFN_STAT_AUX_NOISY)) << method;
            const double albedoShare = estimate(device, "albedo", albedo, 3);
            const double depthShare = estimate(device, "depth", d, 1);
            EXPECT_GT(albedoShare, 0.0);
            EXPECT_GT(depthShare, 0.0);
            EXPECT_FLOAT_EQ(filter.get<float>(AFN_STAT_ALBEDO_SPECKLE), albedoShare)
                << method << " frame " << frame;
            EXPECT_FLOAT_EQ(filter.get<float>(AFN_STAT_DEPTH_SPECKLE), depthShare)
                << method << " frame " << frame;
            EXPECT_EQ(filter.get<float>(AFN_STAT_NORMAL_SPECKLE), 0.0f) << method;
        }
    }
}
