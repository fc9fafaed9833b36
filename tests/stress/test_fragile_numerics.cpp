// SPDX-License-Identifier: Apache-2.0
// Numerics that are fragile by nature, driven through the public API with crafted inputs:
//   - softmax of large logits: AFN's kernel heads scaled up to overflow (crafted weights archives);
//   - BMFR's least squares on rank-deficient blocks (flat normals, constant positions, zero albedo,
//     no features), with and without its feature noise;
//   - SVGF with zero variance (constant regions, sigmaL = 0): a single frame stays within the range
//     of its input;
//   - divisions by albedo at and around the albedo floor, for every method.
#include "afnw_edit.h"
#include "stress_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

using namespace stress;

namespace {

bool hasMethod(const std::string& m)
{
    const std::vector<std::string> all = allMethods();
    return std::find(all.begin(), all.end(), m) != all.end();
}

/// Per-channel [min, max] of the colour plane.
void colorRange(const FrameData& f, float lo[3], float hi[3])
{
    const std::vector<float>& c = f.plane("color");
    for (int k = 0; k < 3; ++k) {
        lo[k] = FLT_MAX;
        hi[k] = -FLT_MAX;
    }
    for (std::size_t i = 0; i < c.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], c[i]);
        hi[i % 3] = std::max(hi[i % 3], c[i]);
    }
}

/// Every output colour value lies in the input's per-channel range (with a relative slack).
::testing::AssertionResult withinInputRange(
    const FrameData& in, const FrameResult& out, double slack)
{
    float lo[3], hi[3];
    colorRange(in, lo, hi);
    for (std::size_t i = 0; i < out.output.size(); ++i) {
        const int c = static_cast<int>(i % out.channels);
        if (c > 2)
            continue;
        const double v = out.output[i];
        if (!(v >= lo[c] * (1.0 - slack) && v <= hi[c] * (1.0 + slack)))
            return ::testing::AssertionFailure()
                << "value " << i << " = " << v << " outside [" << lo[c] << ", " << hi[c] << "]";
    }
    return ::testing::AssertionSuccess();
}

// ---- softmax of large logits -------------------------------------------------------------------

TEST(FragileNumerics, SoftmaxOfLargeLogitsStaysFiniteAndBounded)
{
    if (!hasMethod("afn"))
        GTEST_SKIP() << "this build has no afn method";
    // The fusion variant: the output is the kernels' filtering and fusion, no refinement residual.
    const std::vector<char> base = readFile(AFN_TEST_DATA "/afn_parity/weights_fusion.afnw");
    ASSERT_FALSE(base.empty());
    std::vector<FrameData> seq;
    for (int f = 0; f < 3; ++f)
        seq.push_back(plausibleFrame(29, 23, f));
    for (const float scale : { 1.0f, 1e3f, 1e8f, 1e20f, 1e30f, 1e36f, FLT_MAX }) {
        SCOPED_TRACE("kernel heads scaled by " + std::to_string(scale));
        RunOptions opt;
        opt.weights = base;
        forEachTensor(opt.weights, [&](const std::string& name, float* v, std::size_t n) {
            if (name.rfind("head", 0) != 0)
                return;
            // FLT_MAX: every weight becomes +-FLT_MAX / 2 (finite), so that the logits overflow
            // to +-Inf, and to NaN where Inf - Inf meet.
            for (std::size_t i = 0; i < n; ++i)
                v[i] = scale == FLT_MAX ? std::copysign(FLT_MAX / 2, v[i]) : v[i] * scale;
        });
        std::string error;
        const auto out = runSequence("afn", seq, opt, &error);
        ASSERT_EQ(error, "");
        for (std::size_t k = 0; k < out.size(); ++k) {
            std::string where;
            EXPECT_TRUE(allFinite(out[k].output, &where)) << "frame " << k << ": " << where;
            const double mean = sanitisedColorMean(seq[k]);
            EXPECT_LE(outputMean(out[k]), 4.0 * mean) << "frame " << k;
            EXPECT_GE(outputMean(out[k]), mean / 4.0) << "frame " << k;
        }
    }
}

TEST(FragileNumerics, WeightsWithNonFiniteValuesAreRejected)
{
    if (!hasMethod("afn"))
        GTEST_SKIP() << "this build has no afn method";
    for (const float bad : { std::nanf(""), INFINITY, -INFINITY }) {
        std::vector<char> w = readFile(AFN_TEST_DATA "/afn_parity/weights_fusion.afnw");
        forEachTensor(w, [&](const std::string& name, float* v, std::size_t) {
            if (name == "head1.weight")
                v[3] = bad;
        });
        afn::DeviceRef device = afn::newDevice();
        device.commit();
        afn::FilterRef filter = device.newFilter("afn");
        filter.setData("weights", w.data(), w.size());
        std::string message;
        EXPECT_EQ(device.getError(&message), afn::Error::InvalidArgument) << bad;
        EXPECT_NE(message.find("head1.weight"), std::string::npos) << message;
    }
}

// ---- BMFR least squares on rank-deficient blocks -----------------------------------------------

/// A frame with flat normals, positions on a plane (z constant) and colour a linear ramp in x.
FrameData rampFrame(int w, int h, bool constantPositions)
{
    FrameData f = plausibleFrame(w, h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            for (int c = 0; c < 3; ++c) {
                f.plane("albedo")[i * 3 + c] = 0.5f;
                f.plane("color")[i * 3 + c]
                    = 0.5f * (0.2f + 0.6f * static_cast<float>(x) / static_cast<float>(w));
                f.plane("normal")[i * 3 + c] = c == 2 ? 1.0f : 0.0f;
                f.plane("position")[i * 3 + c] = constantPositions ? 1.0f
                                                                   : (c == 0        ? 0.01f * x
                                                                           : c == 1 ? 0.01f * y
                                                                                    : 5.0f);
            }
            f.plane("depth")[i] = 5.0f;
        }
    return f;
}

TEST(FragileNumerics, BmfrFitsRankDeficientBlocks)
{
    if (!hasMethod("bmfr"))
        GTEST_SKIP() << "this build has no bmfr method";
    for (const float noise : { 0.0f, 0.01f }) {
        RunOptions opt;
        opt.floats["noise"] = noise;
        SCOPED_TRACE("feature noise " + std::to_string(noise));
        std::string error;
        // Flat normals and z: those columns are constant or zero, yet x and y explain the ramp.
        const FrameData ramp = rampFrame(70, 40, false);
        auto out = runSequence("bmfr", { ramp }, opt, &error);
        ASSERT_EQ(error, "");
        const std::vector<float>& c = ramp.plane("color");
        double worst = 0.0;
        for (std::size_t i = 0; i < c.size(); ++i)
            worst = std::max(worst,
                std::fabs(static_cast<double>(out[0].output[i / 3 * 4 + i % 3]) - c[i]) / c[i]);
        if (noise == 0.0f) // with the noise the fit is only close
            EXPECT_LE(worst, 1e-3) << "the ramp is not reproduced";
        EXPECT_TRUE(withinInputRange(ramp, out[0], noise > 0.0f ? 0.1 : 1e-5));
        // Constant positions and normals: only the constant column is left, the fit is a mean.
        const FrameData flat = rampFrame(70, 40, true);
        out = runSequence("bmfr", { flat }, opt, &error);
        ASSERT_EQ(error, "");
        EXPECT_TRUE(withinInputRange(flat, out[0], 1e-5));
        // No albedo-divisible pixel at all (albedo 0): every pixel keeps its own value.
        FrameData black = plausibleFrame(70, 40, 0);
        std::fill(black.plane("albedo").begin(), black.plane("albedo").end(), 0.0f);
        out = runSequence("bmfr", { black }, opt, &error);
        ASSERT_EQ(error, "");
        for (std::size_t i = 0; i < black.plane("color").size(); ++i)
            ASSERT_EQ(out[0].output[i / 3 * 4 + i % 3], black.plane("color")[i]) << i;
        // No features at all (colour only): screen coordinates stand in.
        FrameData bare;
        bare.width = ramp.width;
        bare.height = ramp.height;
        bare.planes["color"] = ramp.plane("color");
        out = runSequence("bmfr", { bare, bare, bare }, opt, &error);
        ASSERT_EQ(error, "");
        for (const FrameResult& r : out)
            EXPECT_TRUE(withinInputRange(bare, r, 0.05));
    }
}

// ---- SVGF at zero variance ---------------------------------------------------------------------

TEST(FragileNumerics, SvgfAtZeroVarianceStaysWithinItsInput)
{
    if (!hasMethod("svgf"))
        GTEST_SKIP() << "this build has no svgf method";
    // Half the frame constant (variance exactly 0), half noisy, a 1-ulp step in the constant part.
    FrameData f = plausibleFrame(40, 24, 0);
    std::vector<float>& c = f.plane("color");
    for (std::size_t i = 0; i < c.size(); ++i)
        if ((i / 3) % 40 < 20)
            c[i] = (i / 3) % 40 == 10 ? std::nextafter(0.25f, 1.0f) : 0.25f;
    f.planes.erase("albedo"); // the output range is then the input's
    for (const float sigmaL : { 4.0f, 0.0f, 1000.0f }) {
        SCOPED_TRACE("sigmaL " + std::to_string(sigmaL));
        RunOptions opt;
        opt.floats["sigmaL"] = sigmaL;
        std::string error;
        const auto out = runSequence("svgf", { f }, opt, &error);
        ASSERT_EQ(error, "");
        std::string where;
        EXPECT_TRUE(allFinite(out[0].output, &where)) << where;
        EXPECT_TRUE(withinInputRange(f, out[0], 1e-6));
    }
}

// ---- divisions by albedo near zero -------------------------------------------------------------

TEST(FragileNumerics, AlbedoAroundTheFloorForEveryMethod)
{
    const float floor = 1.0f / 1024.0f;
    const float albedos[] = { 0.0f, 1e-45f, 1e-30f, 1e-8f, floor / 2, std::nextafter(floor, 0.0f),
        floor, std::nextafter(floor, 1.0f), 2 * floor, 0.01f, 1.0f };
    for (const std::string& method : allMethods())
        for (const float a : albedos) {
            SCOPED_TRACE(method + " with albedo " + std::to_string(a));
            // Consistent colour (albedo times lighting), plus pixels of that albedo among others.
            FrameData f = plausibleFrame(33, 19, 0);
            for (std::size_t p = 0; p < static_cast<std::size_t>(33 * 19); ++p)
                if (p % 3 == 0)
                    for (int k = 0; k < 3; ++k) {
                        f.plane("albedo")[p * 3 + k] = a;
                        f.plane("color")[p * 3 + k] = a * 0.8f;
                    }
            std::string error;
            const auto out = runSequence(method, { f, f }, {}, &error);
            ASSERT_EQ(error, "");
            for (const FrameResult& r : out) {
                std::string where;
                EXPECT_TRUE(allFinite(r.output, &where)) << where;
                const double mean = sanitisedColorMean(f);
                EXPECT_LE(outputMean(r), 4.0 * mean);
                EXPECT_GE(outputMean(r), mean / 4.0);
            }
            if (method == "ta") // one frame of TA is demodulation and remodulation only
                for (std::size_t i = 0; i < f.plane("color").size(); ++i) {
                    const float want = f.plane("color")[i];
                    ASSERT_NEAR(out[0].output[i / 3 * 4 + i % 3], want, 2.5e-7f * want) << i;
                }
        }
}

} // namespace
