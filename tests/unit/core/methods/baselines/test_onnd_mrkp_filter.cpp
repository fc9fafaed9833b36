// SPDX-License-Identifier: Apache-2.0
// The "onnd" and "mrkp" filter types: take weights as data (rejecting corrupt ones and another
// model's archive without losing the previous), denoise a small still sequence
// (afntest::StillFrame) to finite non-negative output; ONND's recurrent state is the filter's
// history (afnResetFilter restarts it, so the first frame after a reset equals the first frame of a
// new filter).
#include "afn_test_util.h"
#include "base/exception.h"
#include "filter/registry.h"
#include "still_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

namespace {

using afntest::readBytes;

constexpr int kWidth = 23, kHeight = 13;

/// Executes `count` frames of the still sequence; the last frame's output.
std::vector<float> runFrames(afn::Filter& f, afntest::StillFrame& fr, int count)
{
    std::vector<float> last;
    for (int k = 0; k < count; ++k) {
        f.execute();
        for (std::size_t i = 0; i < fr.out.size(); ++i) {
            EXPECT_TRUE(std::isfinite(fr.out.data()[i]));
            EXPECT_GE(fr.out.data()[i], 0.0f);
        }
        last.assign(fr.out.data(), fr.out.data() + fr.out.size());
    }
    return last;
}

void loadParityWeights(afn::Filter& f, const std::string& name)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/baselines_parity/";
    const auto other = readBytes(dir + (name == "onnd" ? "mrkp" : "onnd") + "_weights.afnw");
    EXPECT_THROW(f.setData("weights", other.data(), other.size()), afn::Exception);
    EXPECT_THROW(f.setData("weights", "garbage", 7), afn::Exception);
    const auto bytes = readBytes(dir + name + "_weights.afnw");
    f.setData("weights", bytes.data(), bytes.size());
    EXPECT_THROW(f.setData("weights", bytes.data(), bytes.size() / 2), afn::Exception);
}

} // namespace

TEST(BaselineFilters, OnndStateIsTheHistory)
{
    afntest::StillFrame fr(kWidth, kHeight);
    auto f = afn::createFilter("onnd");
    fr.bindTo(*f);
    loadParityWeights(*f, "onnd");
    f->commit(); // the valid weights survived the failed replacement
    const std::vector<float> first = runFrames(*f, fr, 1);
    const std::vector<float> later = runFrames(*f, fr, 2); // frames 1, 2 with state
    f->reset();
    EXPECT_EQ(runFrames(*f, fr, 1), first); // a reset starts a new history
    auto g = afn::createFilter("onnd");
    fr.bindTo(*g);
    loadParityWeights(*g, "onnd");
    g->commit();
    g->execute(); // frame 2 without the state of frames 0 and 1
    const std::vector<float> fresh(fr.out.data(), fr.out.data() + fr.out.size());
    double diff = 0.0;
    for (std::size_t i = 0; i < fresh.size(); ++i)
        diff = std::max(diff, static_cast<double>(std::fabs(fresh[i] - later[i])));
    EXPECT_GT(diff, 1e-6); // the recurrent state (and the accumulation) changed frame 2
}

TEST(BaselineFilters, MrkpDenoises)
{
    afntest::StillFrame fr(kWidth, kHeight);
    auto f = afn::createFilter("mrkp");
    fr.bindTo(*f);
    loadParityWeights(*f, "mrkp");
    f->commit();
    runFrames(*f, fr, 3);
}

TEST(BaselineFilters, TypesAreRegisteredWithFeatures)
{
    for (const char* name : { "onnd", "mrkp" }) {
        const afn::FilterType* t = afn::findFilterType(name);
        ASSERT_NE(t, nullptr) << name;
        EXPECT_EQ(t->features.size(), 6u) << name; // the last: historyTrust (every history)
        EXPECT_TRUE(t->stages.accumulate) << name;
    }
}
