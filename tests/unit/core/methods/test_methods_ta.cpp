// SPDX-License-Identifier: Apache-2.0
// Demodulation and temporal accumulation ("ta"): the alpha schedule and lag of TA after a step
// change of the light (static camera), exact round trips for zero albedo, clamping of absurd
// values.
#include "base/exception.h"
#include "stages/demodulate.h"
#include "stages/temporal_accumulation.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using afn::Image;
using methods_test::Buffers;
using methods_test::makeImage;
using methods_test::runFrame;

constexpr int W = 8, H = 6;

TEST(MethodsDemodulate, ZeroAndTinyAlbedoRoundTripExactly)
{
    afn::Frame f;
    f.width = 3;
    f.height = 1;
    f.color = makeImage(3, 1, 3, [](int x, int, int c) { return 0.3f + 0.1f * x + 0.01f * c; });
    f.albedo = makeImage(3, 1, 3, [](int x, int, int) {
        return x == 0 ? 0.0f : x == 1 ? 1e-6f : 0.5f;
    });
    Image irr, back;
    afn::demodulate(f, irr);
    afn::remodulate(f, irr, back);
    EXPECT_TRUE(methods_test::bitEqual(back, f.color));
    // Zero albedo divides by the 2^-10 floor, not by zero.
    EXPECT_EQ(irr(0, 0, 0), f.color(0, 0, 0) * 1024.0f);
}

TEST(MethodsDemodulate, PreDemodulatedColourIsRemodulatedByPlainAlbedo)
{
    afn::Frame f;
    f.width = 2;
    f.height = 1;
    f.colorDemodulated = true;
    f.color = Image(2, 1, 3, 2.0f);
    f.albedo = makeImage(2, 1, 3, [](int x, int, int) { return x == 0 ? 0.0f : 0.25f; });
    Image irr, out;
    afn::demodulate(f, irr);
    EXPECT_EQ(irr(0, 0, 0), 2.0f); // untouched
    afn::remodulate(f, irr, out);
    EXPECT_EQ(out(0, 0, 0), 0.0f); // BMFR: albedo * irradiance
    EXPECT_EQ(out(1, 0, 1), 0.5f);
}

TEST(MethodsDemodulate, HugeValuesAreClampedFinite)
{
    afn::Frame f;
    f.width = 1;
    f.height = 1;
    f.color = Image(1, 1, 3, 3e38f);
    f.albedo = Image(1, 1, 3, 0.0f);
    Image irr;
    afn::demodulate(f, irr);
    EXPECT_EQ(irr(0, 0, 0), afn::kMaxIrradiance);
    EXPECT_TRUE(std::isfinite(irr(0, 0, 0) * irr(0, 0, 0)));
}

/// Expected TA value of an always-accepted pixel: the schedule of the notes, frame k blends with
/// alpha_k = max(1 / (k + 1), 0.2) (alpha_0 = 1).
std::vector<double> expectedSchedule(const std::vector<float>& values)
{
    std::vector<double> out;
    double acc = 0.0;
    for (std::size_t k = 0; k < values.size(); ++k) {
        const double a = std::max(1.0 / static_cast<double>(k + 1), 0.2);
        acc = k == 0 ? values[0] : (1.0 - a) * acc + a * values[k];
        out.push_back(acc);
    }
    return out;
}

TEST(MethodsTa, MovingLightShowsTheDocumentedLag)
{
    // Static camera; the light switches from 0.2 to 1.0 at frame 3 and back to 0.5 at frame 12.
    std::vector<float> light;
    for (int k = 0; k < 20; ++k)
        light.push_back(k < 3 ? 0.2f : k < 12 ? 1.0f : 0.5f);
    const std::vector<double> expect = expectedSchedule(light);
    auto ta = afn::createFilter("ta");
    ta->params().setNumber("antilag", 0.0, AFN_PARAM_FLOAT); // BMFR's schedule, no history trust
    Buffers b;
    b.albedo = Image(W, H, 3, 0.5f);
    b.normal = makeImage(W, H, 3, [](int, int, int c) { return c == 2 ? 1.0f : 0.0f; });
    b.position = makeImage(W, H, 3, [](int x, int y, int c) {
        return c == 0 ? x : c == 1 ? y : 3.0f;
    });
    for (std::size_t k = 0; k < light.size(); ++k) {
        b.color = Image(W, H, 3, light[k] * 0.5f); // radiance = albedo * light
        runFrame(*ta, b);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                ASSERT_NEAR(b.out(x, y, 1), 0.5 * expect[k], 1e-6) << "frame " << k;
    }
    // The lag is real: 5 frames after the step the output is still short of the new value.
    EXPECT_LT(expect[7], 0.95);
}

TEST(MethodsTa, HistoryLengthCountsAndSaturates)
{
    afn::Frame f;
    f.width = 2;
    f.height = 2;
    f.color = Image(2, 2, 3, 1.0f);
    afn::Reprojector r;
    afn::TemporalAccumulator ta;
    for (int k = 0; k < 300; ++k) {
        r.compute(f);
        ta.accumulate(r, f.color);
        r.storeGeometry(f);
        ASSERT_EQ(ta.historyLength()(1, 1, 0), std::min(k + 1, 255)) << k;
    }
}

TEST(MethodsTa, ResetRestartsFromTheCurrentFrame)
{
    auto ta = afn::createFilter("ta");
    ta->params().setNumber("antilag", 0.0, AFN_PARAM_FLOAT); // a step of the light, kept
    Buffers b;
    b.color = Image(W, H, 3, 1.0f);
    runFrame(*ta, b);
    b.color = Image(W, H, 3, 0.0f);
    runFrame(*ta, b);
    EXPECT_FLOAT_EQ(b.out(0, 0, 0), 0.5f);
    ta->reset();
    runFrame(*ta, b);
    EXPECT_EQ(b.out(0, 0, 0), 0.0f);
}

TEST(MethodsTa, ParametersAreDescribed)
{
    const afn::FilterType* t = afn::findFilterType("ta");
    ASSERT_NE(t, nullptr);
    bool found = false;
    for (const afn::ParamDesc& d : t->params)
        if (d.name == "alphaMin") {
            found = true;
            EXPECT_EQ(d.defaultValue, 0.2);
            EXPECT_FALSE(d.help.empty());
        }
    EXPECT_TRUE(found);
    auto f = afn::createFilter("ta");
    EXPECT_EQ(f->params().getNumber("positionLimit"), 4.0f);
    EXPECT_EQ(f->params().getNumber("normalLimitSquared"), 0.25f);
}

TEST(MethodsTa, FrameSizeChangeMidSequenceThrows)
{
    auto ta = afn::createFilter("ta");
    ta->params().setNumber("antilag", 0.0, AFN_PARAM_FLOAT); // a step of the light, kept
    Buffers b;
    b.color = Image(W, H, 3, 1.0f);
    runFrame(*ta, b);
    Buffers c;
    c.color = Image(W + 2, H, 3, 1.0f);
    try {
        runFrame(*ta, c);
        FAIL() << "no exception";
    } catch (const afn::Exception& e) {
        EXPECT_NE(std::string(e.what()).find("differs from the previous frame"), std::string::npos)
            << e.what();
    }
}

} // namespace
