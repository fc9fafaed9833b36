// SPDX-License-Identifier: Apache-2.0
// Determinism through the C API, for every method the library reports: the outputs of a sequence
// are bit-identical for 1, 2 and all threads and across repeated runs (fresh devices and filters),
// adversarial frames included; so are the counts of replaced values.
#include "adversarial_cases.h"

#include <gtest/gtest.h>

using namespace stress;

namespace {

class Determinism : public ::testing::TestWithParam<std::string> { };

std::vector<FrameData> sequence()
{
    std::vector<FrameData> seq;
    for (int f = 0; f < 6; ++f)
        seq.push_back(plausibleFrame(45, 37, f, 7));
    applyCase({ "color", "nan-some" }, seq[2]);
    applyCase({ "color", "range-1e30" }, seq[3]);
    applyCase({ "albedo", "black-some" }, seq[4]);
    return seq;
}

TEST_P(Determinism, BitIdenticalForAnyThreadCountAndRepeatedRuns)
{
    const std::string method = GetParam();
    const std::vector<FrameData> seq = sequence();
    std::vector<std::vector<FrameResult>> runs;
    for (const int threads : { 1, 2, 2, 0, 1 }) {
        RunOptions opt;
        opt.threads = threads;
        std::string error;
        runs.push_back(runSequence(method, seq, opt, &error));
        ASSERT_EQ(error, "") << threads << " threads";
        ASSERT_EQ(runs.back().size(), seq.size());
    }
    for (std::size_t r = 1; r < runs.size(); ++r)
        for (std::size_t f = 0; f < seq.size(); ++f) {
            std::string where;
            EXPECT_TRUE(bitIdentical(runs[0][f].output, runs[r][f].output, &where))
                << "run " << r << ", frame " << f << ": " << where;
            EXPECT_EQ(runs[0][f].nonFinite, runs[r][f].nonFinite);
            EXPECT_EQ(runs[0][f].negative, runs[r][f].negative);
        }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Determinism, ::testing::ValuesIn(allMethods()),
    [](const ::testing::TestParamInfo<std::string>& info) { return testName(info.param); });

} // namespace
