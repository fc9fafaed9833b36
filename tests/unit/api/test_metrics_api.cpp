// SPDX-License-Identifier: Apache-2.0
// C API of the metrics: error state after every call, strides, thread-count independence.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace {

struct MetricsApi : ::testing::Test {
    afn::DeviceRef device;
    void SetUp() override
    {
        device = afn::newDevice();
        device.commit();
        ASSERT_EQ(device.getError(), afn::Error::None);
    }
};

std::vector<float> pattern(int w, int h, int ch, int seed)
{
    std::vector<float> v(static_cast<size_t>(w) * h * ch);
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = 0.013f * static_cast<float>((i * 31 + seed) % 89);
    return v;
}

TEST_F(MetricsApi, KnownValuesThroughTheCApi)
{
    // 2x2 RGBA; one of the 12 RGB values differs by T = 1, the alpha channel differs everywhere.
    std::vector<float> ref(16, 0.0f), test(16, 0.0f);
    for (int p = 0; p < 4; ++p)
        test[p * 4 + 3] = 5.0f;
    test[1 * 4 + 2] = 1.0f;
    AFNMetrics m {};
    ASSERT_TRUE(afn::computeMetrics(device, test.data(), ref.data(), 2, 2, 4, m));
    EXPECT_EQ(device.getError(), afn::Error::None);
    EXPECT_NEAR(m.psnr, 10.0 * std::log10(12.0), 1e-12);
    EXPECT_NEAR(m.rmse, std::sqrt(1.0 / 12.0), 1e-12);
    EXPECT_NEAR(m.smape, (1.0 / 1.001) / 12.0, 1e-12);
    EXPECT_EQ(m.nonFiniteTest, 0);
}

TEST_F(MetricsApi, ErrorsAreRecordedNotThrown)
{
    std::vector<float> img(4 * 4 * 3, 0.5f);
    AFNMetrics m {};
    std::string msg;
    EXPECT_FALSE(afnComputeMetrics(device.getHandle(), nullptr, img.data(), 4, 4, 3, &m));
    EXPECT_EQ(device.getError(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("test"), std::string::npos);
    EXPECT_FALSE(afnComputeMetrics(device.getHandle(), img.data(), img.data(), 4, 4, 2, &m));
    EXPECT_EQ(device.getError(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("pixelFloatStride"), std::string::npos);
    EXPECT_FALSE(afnComputeMetrics(device.getHandle(), img.data(), img.data(), 0, 4, 3, &m));
    EXPECT_EQ(device.getError(), afn::Error::InvalidArgument);
    EXPECT_FALSE(afnComputeMetrics(device.getHandle(), img.data(), img.data(), 4, 4, 3, nullptr));
    EXPECT_EQ(device.getError(), afn::Error::InvalidArgument);
    EXPECT_FALSE(afnComputeMetrics(nullptr, img.data(), img.data(), 4, 4, 3, &m));
    EXPECT_EQ(afnGetDeviceError(nullptr, nullptr), AFN_ERROR_INVALID_ARGUMENT);
    AFNTemporalMetrics t {};
    EXPECT_FALSE(afnComputeTemporalMetrics(
        device.getHandle(), img.data(), img.data(), nullptr, img.data(), 4, 4, 3, &t));
    EXPECT_EQ(device.getError(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("previous reference"), std::string::npos);
}

TEST_F(MetricsApi, UncommittedDeviceIsAnError)
{
    afn::DeviceRef d = afn::newDevice();
    std::vector<float> img(4 * 4 * 3, 0.5f);
    AFNMetrics m {};
    EXPECT_FALSE(afn::computeMetrics(d, img.data(), img.data(), 4, 4, 3, m));
    EXPECT_EQ(d.getError(), afn::Error::InvalidOperation);
}

TEST_F(MetricsApi, SameResultsForEveryThreadCount)
{
    const int w = 67, h = 45;
    const std::vector<float> a = pattern(w, h, 3, 1), b = pattern(w, h, 3, 5);
    AFNMetrics m[3];
    AFNTemporalMetrics t[3];
    const int threads[3] = { 1, 2, 0 };
    for (int i = 0; i < 3; ++i) {
        afn::DeviceRef d = afn::newDevice();
        d.set("numThreads", threads[i]);
        d.commit();
        ASSERT_TRUE(afn::computeMetrics(d, a.data(), b.data(), w, h, 3, m[i]));
        ASSERT_TRUE(
            afn::computeTemporalMetrics(d, a.data(), b.data(), b.data(), a.data(), w, h, 3, t[i]));
    }
    for (int i = 1; i < 3; ++i) {
        EXPECT_EQ(std::memcmp(&m[0], &m[i], sizeof(AFNMetrics)), 0);
        EXPECT_EQ(std::memcmp(&t[0], &t[i], sizeof(AFNTemporalMetrics)), 0);
    }
    EXPECT_GT(t[0].gradientError, 0.0);
}

} // namespace
