// SPDX-License-Identifier: Apache-2.0
// 10,000 frames of a static scene through every method (tiny frames, so that it is quick):
//   - a noisy static scene converges (temporal methods: the output varies less from frame to frame
//     than the input) and does not drift (the mean over frames 1000-2000 equals that over
//     9000-10000);
//   - a constant scene's output at frame 10,000 is bit-identical to its output at frame 4;
//   - a scene that turns black decays to exact zero (learned methods: below kLearnedBlack) and
//     denormal values show only while it decays: a history stuck at denormal values would make
//     every later frame compute on denormals, which is slow.
#include "stress_util.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

using namespace stress;

namespace {

constexpr int kFrames = 10000;
constexpr int kSize = 8;

class LongRuns : public ::testing::TestWithParam<std::string> { };

/// Does the output of frame 1 depend on frame 0 (a temporal method)?
bool isTemporal(const std::string& method)
{
    const FrameData a = plausibleFrame(kSize, kSize, 0), b = plausibleFrame(kSize, kSize, 1);
    const auto withHistory = runSequence(method, { a, b });
    const auto alone = runSequence(method, { b });
    return !bitIdentical(withHistory.at(1).output, alone.at(0).output);
}

/// Mean absolute frame-to-frame change of the colour channels.
double change(const std::vector<float>& a, const std::vector<float>& b, int channels)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (static_cast<int>(i % channels) < 3) {
            sum += std::fabs(static_cast<double>(a[i]) - b[i]);
            ++n;
        }
    return sum / static_cast<double>(n);
}

TEST_P(LongRuns, NoisyStaticSceneConvergesWithoutDrift)
{
    const std::string method = GetParam();
    const bool temporal = isTemporal(method);
    Runner runner(method);
    FrameResult prev, cur;
    double early = 0.0, late = 0.0, outChange = 0.0, inChange = 0.0;
    FrameData prevIn;
    for (int f = 0; f < kFrames; ++f) {
        const FrameData in = plausibleFrame(kSize, kSize, f); // new noise every frame
        ASSERT_TRUE(runner.run(in, cur)) << runner.error() << " at frame " << f;
        ASSERT_TRUE(allFinite(cur.output)) << "frame " << f;
        const double m = outputMean(cur);
        if (f >= 1000 && f < 2000)
            early += m / 1000.0;
        if (f >= kFrames - 1000) {
            late += m / 1000.0;
            outChange += change(cur.output, prev.output, cur.channels) / 1000.0;
            inChange += change(in.plane("color"), prevIn.plane("color"), 3) / 1000.0;
        }
        prev = cur;
        prevIn = in;
    }
    EXPECT_NEAR(late, early, 0.01 * early) << "the output drifts";
    if (temporal)
        EXPECT_LT(outChange, 0.8 * inChange) << "the history does not average the noise";
}

TEST_P(LongRuns, ConstantSceneReachesAFixedPoint)
{
    Runner runner(GetParam());
    const FrameData in = constantFrame(kSize, kSize, 0.37f);
    // Every method settles by frame 4, but afn's network also reads 1 / the history length
    // (its history input), which stops changing when the length reaches its cap of 255 frames.
    const int settled = GetParam() == std::string("afn") ? 300 : 3;
    FrameResult r, atSettled;
    for (int f = 0; f < kFrames; ++f) {
        ASSERT_TRUE(runner.run(in, r)) << runner.error();
        if (f == settled)
            atSettled = r;
    }
    std::string where;
    EXPECT_TRUE(bitIdentical(r.output, atSettled.output, &where)) << where;
}

TEST_P(LongRuns, SceneTurningBlackDecaysToExactZero)
{
    const std::string method = GetParam();
    const double tolerance = takesWeights(method) ? kLearnedBlack : 0.0;
    Runner runner(method);
    const FrameData lit = constantFrame(kSize, kSize, 1.0f),
                    black = constantFrame(kSize, kSize, 0.0f);
    constexpr int kLit = 100;
    // From 1 to FLT_MIN (1.2e-38) at the smallest blend weight of the methods (0.1) takes about
    // 830 frames; allow twice that.
    constexpr int kDecay = 2000;
    FrameResult r;
    int lastDenormal = -1;
    for (int f = 0; f < kFrames; ++f) {
        ASSERT_TRUE(runner.run(f < kLit ? lit : black, r)) << runner.error();
        for (float v : r.output)
            if (v != 0.0f && std::fabs(v) < FLT_MIN)
                lastDenormal = f;
    }
    for (std::size_t i = 0; i < r.output.size(); i += r.channels)
        for (int c = 0; c < 3; ++c)
            ASSERT_LE(std::fabs(r.output[i + c]), tolerance)
                << "pixel " << i / r.channels << " after " << kFrames - kLit << " black frames";
    EXPECT_LT(lastDenormal, kLit + kDecay)
        << "the output still holds denormal values at frame " << lastDenormal;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, LongRuns, ::testing::ValuesIn(allMethods()),
    [](const ::testing::TestParamInfo<std::string>& info) { return testName(info.param); });

} // namespace
