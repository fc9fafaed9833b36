// SPDX-License-Identifier: Apache-2.0
// Every method the library reports, every input role, every class of adversarial values
// (adversarial_cases.h), through the C API. For each case:
//   - in a sequence (plausible frame, adversarial frame, plausible frame) every output value is
//     finite, in every frame, and stats.nonFinite / stats.negative count exactly the NaN/Inf values
//     of all inputs and the negative colour values (the warning afntool prints);
//   - the adversarial frame denoised on its own keeps its energy: the output mean is at most
//     kEnergyFactor times the mean of the sanitised colour (NaN/Inf and negatives as 0; adversarial
//     albedo: times kAlbedoFloorAmplification as well), and at least that mean with every value
//     capped at 1, divided by kEnergyFactor;
//   - the same sequence as a 64-spp file (the detail restoration on): every output value finite
//     and the non-finite and negative inputs counted.
#include "adversarial_cases.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace stress;

namespace {

constexpr int kWidth = 33, kHeight = 19; // odd, more than one BMFR block, padded by AFN
constexpr double kEnergyFactor = 4.0;
/// Output means below this (linear; display white is 1) are not counted as created energy.
constexpr double kEnergyFloor = 1e-3;
/// Garbage albedo leaves some pixels below the albedo floor (2^-10) beside others above it: their
/// colour, divided by the floor, may spread up to 1024x amplified into neighbours that are then
/// remodulated with their own albedo (svgf and afn filter the demodulated colour). Such pixels are
/// ordinary (sky, saturated materials), so the methods keep them; the bound is the floor's
/// amplification (docs/reliability.md, known limitations).
constexpr double kAlbedoFloorAmplification = 1024.0;

class AdversarialValues : public ::testing::TestWithParam<std::string> { };

/// The sequence (plausible frame, `c` applied to one, plausible frame) through `method`: every
/// output value finite, stats.nonFinite and stats.negative counting exactly the inputs'.
void expectFiniteAndCounted(
    const std::string& method, const AdversarialCase& c, const RunOptions& options)
{
    FrameData bad = plausibleFrame(kWidth, kHeight, 1);
    applyCase(c, bad);
    const std::vector<FrameData> seq
        = { plausibleFrame(kWidth, kHeight, 0), bad, plausibleFrame(kWidth, kHeight, 2) };
    std::string error;
    const std::vector<FrameResult> out = runSequence(method, seq, options, &error);
    ASSERT_EQ(error, "");
    ASSERT_EQ(out.size(), seq.size());
    for (std::size_t k = 0; k < seq.size(); ++k) {
        std::string where;
        EXPECT_TRUE(allFinite(out[k].output, &where)) << "frame " << k << ": " << where;
        EXPECT_EQ(out[k].nonFinite, countNonFinite(seq[k])) << "frame " << k;
        EXPECT_EQ(out[k].negative, countNegativeColor(seq[k])) << "frame " << k;
    }
}

TEST_P(AdversarialValues, FiniteOutputCountedWarningsBoundedEnergy)
{
    const std::string method = GetParam();
    for (const AdversarialCase& c : adversarialCases()) {
        SCOPED_TRACE(method + " with " + c.name());
        expectFiniteAndCounted(method, c, {});
        FrameData bad = plausibleFrame(kWidth, kHeight, 1);
        applyCase(c, bad);
        std::string error;
        const std::vector<FrameResult> single = runSequence(method, { bad }, {}, &error);
        ASSERT_EQ(error, "");
        const double mean = sanitisedColorMean(bad);
        const double capped = sanitisedColorMean(bad, 1.0);
        const double got = outputMean(single.at(0));
        const double factor
            = c.role == "albedo" ? kEnergyFactor * kAlbedoFloorAmplification : kEnergyFactor;
        EXPECT_LE(got, factor * std::max(mean, kEnergyFloor))
            << "input mean " << mean << " (capped at 1: " << capped << ")";
        EXPECT_GE(got, capped / kEnergyFactor - 1e-30)
            << "input mean " << mean << " (capped at 1: " << capped << ")";
    }
}

TEST_P(AdversarialValues, FiniteAndCountedAtSixtyFourSpp)
{
    // The same sequences as a 64-spp file: the methods that demodulate then run their detail
    // restoration (stages/detail_restore.h) on the adversarial frame and the frames around it.
    const std::string method = GetParam();
    if (!hasIntParameter(method, "spp"))
        GTEST_SKIP() << method << " has no spp parameter";
    RunOptions options;
    options.ints["spp"] = 64;
    for (const AdversarialCase& c : adversarialCases()) {
        SCOPED_TRACE(method + " with " + c.name());
        expectFiniteAndCounted(method, c, options);
    }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, AdversarialValues, ::testing::ValuesIn(allMethods()),
    [](const ::testing::TestParamInfo<std::string>& info) { return testName(info.param); });

} // namespace
