// SPDX-License-Identifier: Apache-2.0
// API contract tests: every call's error state, including the negative paths (null handles,
// unknown names, out-of-range values, size mismatches, uncommitted execute, cancel).
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace {

struct ApiTest : ::testing::Test {
    afn::DeviceRef device;
    void SetUp() override
    {
        device = afn::newDevice();
        ASSERT_TRUE(device);
        device.commit();
        ASSERT_EQ(device.getError(), afn::Error::None);
    }
    afn::Error error(std::string* msg = nullptr) { return device.getError(msg); }
};

std::vector<float> ramp(int w, int h, int ch)
{
    std::vector<float> v(static_cast<size_t>(w) * h * ch);
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = 0.01f * static_cast<float>(i % 97);
    return v;
}

TEST_F(ApiTest, VersionAndThreads)
{
    EXPECT_EQ(device.get("version"), AFN_VERSION);
    device.set("numThreads", 1);
    EXPECT_EQ(device.get("numThreads"), 1);
    EXPECT_EQ(error(), afn::Error::None);
    device.set("numThreads", -1);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    device.set("noSuchParam", 1);
    std::string msg;
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("noSuchParam"), std::string::npos);
    EXPECT_EQ(error(), afn::Error::None) << "an error is cleared once read";
}

TEST(ApiNull, NullHandlesRecordThreadError)
{
    afnCommitDevice(nullptr);
    const char* msg = nullptr;
    EXPECT_EQ(afnGetDeviceError(nullptr, &msg), AFN_ERROR_INVALID_ARGUMENT);
    ASSERT_NE(msg, nullptr);
    EXPECT_NE(std::string(msg).find("invalid device"), std::string::npos);
    afnExecuteFilter(nullptr);
    EXPECT_EQ(afnGetDeviceError(nullptr, nullptr), AFN_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(afnGetDeviceError(nullptr, nullptr), AFN_ERROR_NONE);
    // The thread slot is per thread.
    afnReleaseFilter(nullptr);
    AFNError other = AFN_ERROR_UNKNOWN;
    std::thread([&] { other = afnGetDeviceError(nullptr, nullptr); }).join();
    EXPECT_EQ(other, AFN_ERROR_NONE);
    EXPECT_EQ(afnGetDeviceError(nullptr, nullptr), AFN_ERROR_INVALID_ARGUMENT);
}

TEST(ApiNull, FilterNeedsCommittedDevice)
{
    afn::DeviceRef d = afn::newDevice();
    afn::FilterRef f = d.newFilter("identity");
    EXPECT_FALSE(f);
    EXPECT_EQ(d.getError(), afn::Error::InvalidOperation);
}

TEST_F(ApiTest, UnknownFilterTypeListsKnownOnes)
{
    afn::FilterRef f = device.newFilter("nope");
    EXPECT_FALSE(f);
    std::string msg;
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("identity"), std::string::npos) << msg;
}

TEST_F(ApiTest, IntrospectionMatchesTypes)
{
    const auto types = afn::filterTypes();
    ASSERT_FALSE(types.empty());
    for (const std::string& t : types) {
        const int n = afnGetFilterTypeNumParams(t.c_str());
        ASSERT_GE(n, 1) << t;
        for (int i = 0; i < n; ++i) {
            AFNParamInfo info {};
            ASSERT_TRUE(afnGetFilterTypeParam(t.c_str(), i, &info));
            EXPECT_NE(info.help, nullptr);
            EXPECT_GT(std::strlen(info.help), 5u) << info.name;
            if (info.type != AFN_PARAM_STRING) {
                EXPECT_LE(info.minValue, info.defaultValue) << info.name;
                EXPECT_LE(info.defaultValue, info.maxValue) << info.name;
            }
        }
        AFNParamInfo info {};
        EXPECT_FALSE(afnGetFilterTypeParam(t.c_str(), n, &info));
    }
    EXPECT_EQ(afnGetFilterTypeNumParams("nope"), -1);
    EXPECT_EQ(afnGetFilterTypeName(-1), nullptr);
}

TEST_F(ApiTest, ParameterValidation)
{
    afn::FilterRef f = device.newFilter("identity");
    ASSERT_TRUE(f);
    f.set("normal.space", "camera");
    EXPECT_EQ(error(), afn::Error::None);
    EXPECT_EQ(f.get<std::string>("normal.space"), "camera");
    f.set("normal.space", "sideways");
    std::string msg;
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("world|camera"), std::string::npos) << msg;
    f.set("motion.scale", -2.0f);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.set("motion.scale", std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.set("motion.scale", "0.5");
    EXPECT_EQ(error(), afn::Error::None);
    EXPECT_FLOAT_EQ(f.get<float>("motion.scale"), 0.5f);
    f.set("motion.scale", "half");
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.set("unknown.param", 1);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    const float four[4] = { 0, 0, 0, 0 };
    f.setFloats("viewProjection", four, 4);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
}

TEST_F(ApiTest, CommitValidatesImages)
{
    afn::FilterRef f = device.newFilter("identity");
    std::vector<float> color = ramp(8, 4, 3), out(8 * 4 * 3), small = ramp(4, 4, 3);
    f.commit();
    std::string msg;
    EXPECT_EQ(error(&msg), afn::Error::InvalidOperation) << "no colour";
    f.setImage("color", color.data(), afn::Format::Float3, 8, 4);
    f.commit();
    EXPECT_EQ(error(&msg), afn::Error::InvalidOperation) << "no output";
    EXPECT_NE(msg.find("output"), std::string::npos);
    f.setImage("output", out.data(), afn::Format::Float3, 8, 4);
    f.setImage("albedo", small.data(), afn::Format::Float3, 4, 4);
    f.commit();
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("albedo size 4x4 does not match color 8x4"), std::string::npos) << msg;
    f.unsetImage("albedo");
    f.setImage("bogus", color.data(), afn::Format::Float3, 8, 4);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.setImage("color", nullptr, afn::Format::Float3, 8, 4);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.setImage("color", color.data(), afn::Format::Float3, 0, 4);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.setImage("color", color.data(), afn::Format::Undefined, 8, 4);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
    f.commit();
    EXPECT_EQ(error(), afn::Error::None);
}

TEST_F(ApiTest, ExecuteRequiresCommit)
{
    afn::FilterRef f = device.newFilter("identity");
    std::vector<float> color = ramp(8, 4, 3), out(8 * 4 * 3);
    f.setImage("color", color.data(), afn::Format::Float3, 8, 4);
    f.setImage("output", out.data(), afn::Format::Float3, 8, 4);
    f.execute();
    EXPECT_EQ(error(), afn::Error::InvalidOperation);
    f.commit();
    f.execute();
    EXPECT_EQ(error(), afn::Error::None);
    EXPECT_EQ(out, color);
    f.set("motion.scale", 2.0f);
    f.execute();
    EXPECT_EQ(error(), afn::Error::InvalidOperation) << "parameter change needs a new commit";
}

TEST_F(ApiTest, StridedNegativeRowStrideAndRgbaOutput)
{
    // A bottom-up RGBA buffer (as OFX hosts hand them) read through a negative row stride.
    const int w = 5, h = 3;
    std::vector<float> rgbaBottomUp(w * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c)
                rgbaBottomUp[((h - 1 - y) * w + x) * 4 + c] = float(100 * y + 10 * x + c);
    std::vector<float> out(w * h * 4, -1.0f);
    afn::FilterRef f = device.newFilter("identity");
    const ptrdiff_t row = w * 4 * sizeof(float);
    f.setImage("color", rgbaBottomUp.data(), afn::Format::Float4, w, h, (h - 1) * row, 0, -row);
    f.setImage("alpha", rgbaBottomUp.data(), afn::Format::Float, w, h,
        (h - 1) * row + 3 * sizeof(float), 4 * sizeof(float), -row);
    f.setImage("output", out.data(), afn::Format::Float4, w, h);
    f.commit();
    f.execute();
    ASSERT_EQ(error(), afn::Error::None);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c)
                EXPECT_EQ(out[(y * w + x) * 4 + c], float(100 * y + 10 * x + c))
                    << x << "," << y << "," << c;
}

TEST_F(ApiTest, NonFiniteAndNegativeInputsAreSanitisedAndCounted)
{
    std::vector<float> color
        = { 1.0f, std::nanf(""), -2.0f, std::numeric_limits<float>::infinity(), 0.5f, 0.25f };
    std::vector<float> out(6);
    afn::FilterRef f = device.newFilter("identity");
    f.setImage("color", color.data(), afn::Format::Float3, 2, 1);
    f.setImage("output", out.data(), afn::Format::Float3, 2, 1);
    f.commit();
    f.execute();
    ASSERT_EQ(error(), afn::Error::None);
    EXPECT_EQ(out, (std::vector<float> { 1.0f, 0.0f, 0.0f, 0.0f, 0.5f, 0.25f }));
    EXPECT_EQ(f.get<int>("stats.nonFinite"), 2);
    EXPECT_EQ(f.get<int>("stats.negative"), 1);
}

TEST_F(ApiTest, FrameSizeChangeIsAnErrorUntilReset)
{
    afn::FilterRef f = device.newFilter("identity");
    std::vector<float> a = ramp(8, 4, 3), b = ramp(4, 8, 3), out(32 * 3);
    f.setImage("color", a.data(), afn::Format::Float3, 8, 4);
    f.setImage("output", out.data(), afn::Format::Float3, 8, 4);
    f.commit();
    f.execute();
    EXPECT_EQ(f.get<int>("frameIndex"), 1);
    f.setImage("color", b.data(), afn::Format::Float3, 4, 8);
    f.setImage("output", out.data(), afn::Format::Float3, 4, 8);
    f.commit();
    f.execute();
    std::string msg;
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("4x8 differs from the previous frame's 8x4"), std::string::npos) << msg;
    f.reset();
    f.execute();
    EXPECT_EQ(error(), afn::Error::None);
    EXPECT_EQ(f.get<int>("frameIndex"), 1);
}

TEST_F(ApiTest, ProgressCallbackCanCancel)
{
    afn::FilterRef f = device.newFilter("identity");
    std::vector<float> a = ramp(8, 4, 3), out(32 * 3);
    f.setImage("color", a.data(), afn::Format::Float3, 8, 4);
    f.setImage("output", out.data(), afn::Format::Float3, 8, 4);
    f.setProgressMonitorFunction([](void*, double) { return false; });
    f.commit();
    f.execute();
    EXPECT_EQ(error(), afn::Error::Cancelled);
    EXPECT_EQ(f.get<int>("frameIndex"), 0) << "a cancelled frame does not advance the history";
}

TEST_F(ApiTest, ErrorCallbackSeesEveryError)
{
    int calls = 0;
    device.setErrorFunction(
        [](void* user, AFNError, const char*) { ++*static_cast<int*>(user); }, &calls);
    device.newFilter("nope");
    device.newFilter("nope");
    EXPECT_EQ(calls, 2);
    EXPECT_EQ(error(), afn::Error::InvalidArgument);
}

TEST_F(ApiTest, WrapperRefCounting)
{
    afn::FilterRef a = device.newFilter("identity");
    {
        afn::FilterRef b = a; // retain
        afn::FilterRef c = std::move(b);
        EXPECT_FALSE(b);
        EXPECT_TRUE(c);
    }
    EXPECT_EQ(a.get<std::string>("depth.kind"), "planar") << "still alive after the copies went";
    EXPECT_EQ(error(), afn::Error::None);
}

} // namespace

namespace {

TEST(ApiDevice, TypesAndUnsupportedCuda)
{
    afn::DeviceRef cpu = afn::newDevice(afn::DeviceType::CPU);
    ASSERT_TRUE(cpu);
    EXPECT_EQ(cpu.get("type"), AFN_DEVICE_TYPE_CPU);
    afn::DeviceRef def = afn::newDevice();
    ASSERT_TRUE(def);
    EXPECT_EQ(def.get("type"), AFN_DEVICE_TYPE_CPU) << "the default device is the CPU";
    AFNDevice bad = afnNewDevice(static_cast<AFNDeviceType>(99));
    EXPECT_EQ(bad, nullptr);
    EXPECT_EQ(afnGetDeviceError(nullptr, nullptr), AFN_ERROR_INVALID_ARGUMENT);
}

TEST(ApiDevice, SettingsUncommitUntilCommitted)
{
    afn::DeviceRef d = afn::newDevice();
    d.commit();
    afn::FilterRef f = d.newFilter("identity");
    ASSERT_TRUE(f);
    d.set("numThreads", 1); // settings uncommit the device: executes fail until commit
    std::vector<float> in = ramp(4, 4, 3), out(4 * 4 * 3);
    f.setImage(AFN_IMAGE_COLOR, in.data(), afn::Format::Float3, 4, 4);
    f.setImage(AFN_IMAGE_OUTPUT, out.data(), afn::Format::Float3, 4, 4);
    f.commit();
    f.execute();
    std::string msg;
    EXPECT_EQ(d.getError(&msg), afn::Error::InvalidOperation);
    EXPECT_NE(msg.find("not committed"), std::string::npos) << msg;
    d.commit();
    f.execute();
    EXPECT_EQ(d.getError(), afn::Error::None);
    EXPECT_EQ(out, in);
}

TEST(ApiDevice, CommitWhileOtherThreadsExecute)
{
    // Commits and executes on one device from several threads: the device lock orders them, every
    // execute succeeds or reports "not committed", and no run crashes or writes garbage.
    afn::DeviceRef d = afn::newDevice();
    d.commit();
    std::vector<std::thread> workers;
    std::atomic<int> ok { 0 };
    for (int t = 0; t < 3; ++t)
        workers.emplace_back([&] {
            afn::FilterRef f = d.newFilter("svgf");
            std::vector<float> in = ramp(32, 24, 3), out(32 * 24 * 3);
            for (int i = 0; i < 20; ++i) {
                f.setImage(AFN_IMAGE_COLOR, in.data(), afn::Format::Float3, 32, 24);
                f.setImage(AFN_IMAGE_OUTPUT, out.data(), afn::Format::Float3, 32, 24);
                f.commit();
                f.execute();
                for (float v : out)
                    if (!std::isfinite(v))
                        return;
                ++ok;
            }
        });
    for (int i = 0; i < 20; ++i)
        d.commit();
    for (std::thread& w : workers)
        w.join();
    EXPECT_EQ(ok.load(), 60);
}

TEST(ApiFeatures, DescribedPerType)
{
    EXPECT_EQ(afnGetFilterTypeNumFeatures("identity"), 0);
    EXPECT_EQ(afnGetFilterTypeNumFeatures("svgf"), 1); // every method with a history: its trust
    EXPECT_EQ(afnGetFilterTypeNumFeatures("no-such-method"), -1);
    const std::vector<AFNFeatureInfo> f = afn::filterTypeFeatures("afn");
    ASSERT_EQ(f.size(), 7u);
    EXPECT_STREQ(f[0].name, "irradiance");
    EXPECT_EQ(f[4].channels, 1);
    EXPECT_STREQ(f[5].name, "history01");
    EXPECT_EQ(f[5].channels, 1);
    EXPECT_STREQ(f[6].name, "historyTrust");
    EXPECT_EQ(f[6].channels, 1);
    AFNFeatureInfo info {};
    EXPECT_FALSE(afnGetFilterTypeFeature("afn", 7, &info));
}

TEST_F(ApiTest, FeatureOutputsAreTheNetworkInputs)
{
    const int w = 20, h = 12;
    std::vector<float> color = ramp(w, h, 3), albedo(w * h * 3);
    for (size_t i = 0; i < albedo.size(); ++i)
        albedo[i] = i % 5 == 0 ? 0.0f : 0.1f * static_cast<float>(i % 9); // zeros hit the floor
    std::vector<float> irr(w * h * 3, -1.0f), acc(w * h * 3, -1.0f), depth(w * h, -1.0f);
    std::vector<float> out1(w * h * 3), out2(w * h * 3);

    // Features only: no "output", the network does not run. This albedo varies per pixel, so
    // aux=auto would call it noisy; aux=clean demodulates by it as given.
    afn::FilterRef f = device.newFilter("afn");
    f.set(AFN_PARAM_AUX, "clean");
    f.setImage(AFN_IMAGE_COLOR, color.data(), afn::Format::Float3, w, h);
    f.setImage(AFN_IMAGE_ALBEDO, albedo.data(), afn::Format::Float3, w, h);
    f.setImage("feature.irradiance", irr.data(), afn::Format::Float3, w, h);
    f.setImage("feature.accumulated", acc.data(), afn::Format::Float3, w, h);
    f.setImage("feature.depth01", depth.data(), afn::Format::Float, w, h);
    f.commit();
    f.execute();
    ASSERT_EQ(error(), afn::Error::None);
    for (size_t i = 0; i < irr.size(); ++i)
        ASSERT_EQ(irr[i], color[i] / std::max(albedo[i], 1.0f / 1024.0f)) << i;
    EXPECT_EQ(acc, irr) << "first frame: the accumulation is the frame itself";
    for (float v : depth)
        EXPECT_EQ(v, 0.0f) << "no depth input: 0";

    // aux=noisy: the "albedo" feature is the demodulation factor the irradiance was divided by.
    std::vector<float> factor(w * h * 3, -1.0f);
    f.set(AFN_PARAM_AUX, "noisy");
    f.setImage("feature.albedo", factor.data(), afn::Format::Float3, w, h);
    f.commit();
    afnResetFilter(f.getHandle());
    f.execute();
    ASSERT_EQ(error(), afn::Error::None);
    EXPECT_TRUE(f.get<bool>(AFN_STAT_AUX_NOISY));
    EXPECT_NE(factor, albedo) << "the speckled albedo was prefiltered";
    for (size_t i = 0; i < irr.size(); ++i)
        ASSERT_EQ(irr[i], color[i] / std::max(factor[i], 1.0f / 1024.0f)) << i;

    // Binding features does not change the output. Every input: a build may embed only the
    // model for all of them.
    std::vector<float> normal(w * h * 3, 0.5f), motion(w * h * 2, 0.0f);
    afn::FilterRef a = device.newFilter("afn"), b = device.newFilter("afn");
    for (afn::FilterRef* g : { &a, &b }) {
        g->setImage(AFN_IMAGE_COLOR, color.data(), afn::Format::Float3, w, h);
        g->setImage(AFN_IMAGE_ALBEDO, albedo.data(), afn::Format::Float3, w, h);
        g->setImage(AFN_IMAGE_NORMAL, normal.data(), afn::Format::Float3, w, h);
        g->setImage(AFN_IMAGE_DEPTH, color.data(), afn::Format::Float, w, h, 0, 12);
        g->setImage(AFN_IMAGE_MOTION, motion.data(), afn::Format::Float2, w, h);
    }
    a.setImage(AFN_IMAGE_OUTPUT, out1.data(), afn::Format::Float3, w, h);
    b.setImage(AFN_IMAGE_OUTPUT, out2.data(), afn::Format::Float3, w, h);
    b.setImage("feature.irradiance", irr.data(), afn::Format::Float3, w, h);
    for (afn::FilterRef* g : { &a, &b }) {
        g->commit();
        g->execute();
    }
    if (!afn::isFilterTypeReady("afn"))
        GTEST_SKIP() << "this build embeds no AFN weights: the comparison with output needs them";
    ASSERT_EQ(error(), afn::Error::None);
    EXPECT_EQ(out1, out2);
}

TEST_F(ApiTest, FeatureNamesAreChecked)
{
    std::vector<float> px(8 * 8 * 3);
    afn::FilterRef s = device.newFilter("svgf");
    s.setImage("feature.irradiance", px.data(), afn::Format::Float3, 8, 8);
    std::string msg;
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    afn::FilterRef a = device.newFilter("afn");
    a.setImage("feature.nothing", px.data(), afn::Format::Float3, 8, 8);
    EXPECT_EQ(error(&msg), afn::Error::InvalidArgument);
    EXPECT_NE(msg.find("feature.irradiance"), std::string::npos) << msg;
    a.setImage("feature.depth01", px.data(), afn::Format::Float, 8, 8);
    a.setImage(AFN_IMAGE_COLOR, px.data(), afn::Format::Float3, 8, 8);
    a.commit();
    EXPECT_EQ(error(), afn::Error::None) << "a feature output alone is enough to commit";
    s.setImage(AFN_IMAGE_COLOR, px.data(), afn::Format::Float3, 8, 8);
    s.commit();
    EXPECT_EQ(error(&msg), afn::Error::InvalidOperation);
    EXPECT_NE(msg.find("output"), std::string::npos);
}

} // namespace
