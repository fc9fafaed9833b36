// SPDX-License-Identifier: Apache-2.0
// Whole frames and frame shapes for every method the library reports, through the C API:
//   - a constant scene stays exactly constant and an all-black one exactly black, in every frame
//     (learned methods: within the tolerance below, a known limitation in docs/reliability.md);
//   - sizes 1x1, 1xN, Nx1, odd, prime and 8192x4320 give finite output of the right size with
//     bounded energy.
#include "stress_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace stress;

namespace {

class WholeFrames : public ::testing::TestWithParam<std::string> { };

/// Largest |output - value| over the colour channels of every frame.
double maxDeviation(const std::vector<FrameResult>& out, float value)
{
    double dev = 0.0;
    for (const FrameResult& r : out)
        for (std::size_t i = 0; i < r.output.size(); ++i)
            if (static_cast<int>(i % r.channels) < 3)
                dev = std::max(dev, std::fabs(static_cast<double>(r.output[i]) - value));
    return dev;
}

TEST_P(WholeFrames, ConstantStaysConstant)
{
    const std::string method = GetParam();
    const bool learned = takesWeights(method);
    for (const float value : { 0.5f, 3.0f, 1e-3f }) {
        SCOPED_TRACE(method + " at " + std::to_string(value));
        std::string error;
        const auto out = runSequence(
            method, std::vector<FrameData>(4, constantFrame(37, 21, value)), {}, &error);
        ASSERT_EQ(error, "");
        ASSERT_EQ(out.size(), 4u);
        const double tolerance = learned ? kLearnedConstant * value + kLearnedBlack : 1e-6 * value;
        EXPECT_LE(maxDeviation(out, value), tolerance);
    }
}

TEST_P(WholeFrames, BlackStaysBlack)
{
    const std::string method = GetParam();
    std::string error;
    const auto out
        = runSequence(method, std::vector<FrameData>(4, constantFrame(37, 21, 0.0f)), {}, &error);
    ASSERT_EQ(error, "");
    ASSERT_EQ(out.size(), 4u);
    EXPECT_LE(maxDeviation(out, 0.0f), takesWeights(method) ? kLearnedBlack : 0.0);
}

TEST_P(WholeFrames, OddAndDegenerateSizes)
{
    const std::string method = GetParam();
    const int sizes[][2] = { { 1, 1 }, { 1, 2 }, { 2, 1 }, { 1, 37 }, { 37, 1 }, { 2, 2 }, { 3, 5 },
        { 7, 7 }, { 31, 29 }, { 127, 3 }, { 3, 127 }, { 64, 36 } };
    for (const auto& s : sizes) {
        SCOPED_TRACE(method + " at " + std::to_string(s[0]) + "x" + std::to_string(s[1]));
        std::vector<FrameData> seq;
        for (int f = 0; f < 3; ++f)
            seq.push_back(plausibleFrame(s[0], s[1], f));
        std::string error;
        const auto out = runSequence(method, seq, {}, &error);
        ASSERT_EQ(error, "");
        ASSERT_EQ(out.size(), seq.size());
        for (std::size_t k = 0; k < out.size(); ++k) {
            ASSERT_EQ(out[k].output.size(), static_cast<std::size_t>(s[0]) * s[1] * 4);
            std::string where;
            EXPECT_TRUE(allFinite(out[k].output, &where)) << where;
            const double mean = sanitisedColorMean(seq[k]);
            EXPECT_LE(outputMean(out[k]), 4.0 * mean);
            EXPECT_GE(outputMean(out[k]), mean / 4.0);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, WholeFrames, ::testing::ValuesIn(allMethods()),
    [](const ::testing::TestParamInfo<std::string>& info) { return testName(info.param); });

// 8192x4320 (8K DCI-ish, 35 M pixels), colour only, one frame. Run with the two cheapest methods
// only ("identity": binding, gather and output at this size; "ta": reprojection and accumulation):
// svgf, bmfr and afn take minutes at this size on the CI machine and are covered at every other
// size above.
TEST(HugeFrame, FiniteAndExactForTheCheapestMethods)
{
    const int w = 8192, h = 4320;
    FrameData f;
    f.width = w;
    f.height = h;
    std::vector<float>& c = f.planes["color"];
    c.resize(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < c.size(); ++i)
        c[i] = 0.25f + 0.5f * static_cast<float>((i / 3) % 7) / 7.0f;
    c[c.size() / 2] = std::nanf(""); // one bad value in the middle, counted
    const std::vector<std::string> all = allMethods();
    for (const char* method : { "identity", "ta" }) {
        if (std::find(all.begin(), all.end(), method) == all.end())
            continue;
        SCOPED_TRACE(method);
        std::string error;
        const auto out = runSequence(method, { f }, {}, &error);
        ASSERT_EQ(error, "");
        ASSERT_EQ(out.at(0).channels, 3);
        EXPECT_EQ(out[0].nonFinite, 1);
        // Without albedo both methods return the sanitised colour of a first frame exactly.
        for (std::size_t i = 0; i < c.size(); ++i)
            if (out[0].output[i] != (std::isfinite(c[i]) ? c[i] : 0.0f)) {
                ADD_FAILURE() << "value " << i << ": " << out[0].output[i] << " vs " << c[i];
                break;
            }
    }
}

} // namespace
