// SPDX-License-Identifier: Apache-2.0
// afn's output TAA (methods/afn/settings.h, stages/taa.h): the first frame of a history is the
// network's output; a static, repeated frame is a fixed point; on a static camera with changing
// noise it cuts the frame-to-frame change of the output; taa=auto follows the sample count of the
// model that runs (on for the 1-spp models, off for the 16-spp one), bit for bit.
#include "afn_synthetic_sequence.h"
#include "afn_test_util.h"
#include "filter/registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

using afn::Image;
using afntest::SequenceFrame;

constexpr int kW = 48, kH = 32;

std::unique_ptr<afn::Filter> afnFilter(const std::string& taa, bool testWeights = true)
{
    auto f = afn::createFilter("afn");
    f->params().setString("taa", taa);
    if (testWeights) { // the committed parity weights: variant full, 1 spp (no spp metadata)
        const auto w
            = afntest::readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw");
        f->setData(AFN_DATA_WEIGHTS, w.data(), w.size());
    }
    return f;
}

/// Frame `k` of the synthetic scene with its motion zeroed: a static camera and scene whose noise
/// changes with k (noiseFrame) or not (the same k every time).
SequenceFrame staticFrame(int k)
{
    const afntest::SyntheticSequence seq(kW, kH, 5);
    SequenceFrame f = seq.frame(k, afntest::SequenceInputs {});
    SequenceFrame first = seq.frame(0, afntest::SequenceInputs {});
    f.albedo = first.albedo; // the geometry of frame 0, the colour of frame k
    f.normal = first.normal;
    f.depth = first.depth;
    f.position = first.position;
    f.motion = Image(kW, kH, 2);
    return f;
}

double maxAbsDiff(const Image& a, const Image& b)
{
    double m = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        m = std::max(m, static_cast<double>(std::fabs(a.data()[i] - b.data()[i])));
    return m;
}

double meanAbsDiff(const Image& a, const Image& b)
{
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        s += std::fabs(a.data()[i] - b.data()[i]);
    return s / static_cast<double>(a.size());
}

bool identical(const Image& a, const Image& b)
{
    return a.size() == b.size() && std::equal(a.data(), a.data() + a.size(), b.data());
}

} // namespace

TEST(AfnTaa, FirstFrameIsTheNetworkOutput)
{
    auto on = afnFilter("on"), off = afnFilter("off");
    SequenceFrame f = staticFrame(0), g = staticFrame(0);
    Image a(kW, kH, 3), b(kW, kH, 3);
    afntest::runFrame(*on, f, a);
    afntest::runFrame(*off, g, b);
    EXPECT_TRUE(identical(a, b));
}

TEST(AfnTaa, RepeatedStaticFrameIsAFixedPoint)
{
    auto on = afnFilter("on"), off = afnFilter("off");
    Image a(kW, kH, 3), b(kW, kH, 3);
    for (int k = 0; k < 3; ++k) {
        SequenceFrame f = staticFrame(0), g = staticFrame(0);
        afntest::runFrame(*on, f, a);
        afntest::runFrame(*off, g, b);
    }
    // The history equals the current output up to the accumulation's rounding: inside the clamp
    // box, h + 0.5 (c - h) = c.
    EXPECT_LT(maxAbsDiff(a, b), 1e-4);
}

TEST(AfnTaa, CutsTheFrameToFrameChangeOnAStaticCamera)
{
    auto on = afnFilter("on"), off = afnFilter("off");
    Image prevOn, prevOff, a(kW, kH, 3), b(kW, kH, 3);
    double changeOn = 0.0, changeOff = 0.0;
    for (int k = 0; k < 6; ++k) {
        SequenceFrame f = staticFrame(k), g = staticFrame(k);
        afntest::runFrame(*on, f, a);
        afntest::runFrame(*off, g, b);
        if (k >= 2) {
            changeOn += meanAbsDiff(a, prevOn);
            changeOff += meanAbsDiff(b, prevOff);
        }
        prevOn = a;
        prevOff = b;
    }
    EXPECT_FALSE(identical(a, b)); // TAA is active
    EXPECT_LT(changeOn, 0.8 * changeOff) << "on " << changeOn << ", off " << changeOff;
}

TEST(AfnTaa, AutoFollowsTheSampleCountOfTheModel)
{
#ifndef AFN_HAS_EMBEDDED_WEIGHTS
    GTEST_SKIP() << "built without the shipped weights";
#else
    for (const int spp : { 1, 16 }) {
        auto automatic = afnFilter("auto", false), on = afnFilter("on", false),
             off = afnFilter("off", false);
        for (auto* f : { automatic.get(), on.get(), off.get() })
            f->params().setNumber("spp", spp, AFN_PARAM_INT);
        Image a(kW, kH, 3), b(kW, kH, 3), c(kW, kH, 3);
        const afntest::SyntheticSequence seq(kW, kH, 7);
        for (int k = 0; k < 3; ++k) {
            SequenceFrame f = seq.frame(k, {}), g = seq.frame(k, {}), h = seq.frame(k, {});
            afntest::runFrame(*automatic, f, a);
            afntest::runFrame(*on, g, b);
            afntest::runFrame(*off, h, c);
        }
        EXPECT_TRUE(identical(a, spp == 1 ? b : c)) << spp << " spp";
        EXPECT_FALSE(identical(b, c)) << spp << " spp";
    }
#endif
}
