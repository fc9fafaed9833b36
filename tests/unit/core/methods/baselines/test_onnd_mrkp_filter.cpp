// SPDX-License-Identifier: Apache-2.0
// The "onnd" and "mrkp" filter types: take weights as data (rejecting corrupt ones and another
// model's archive without losing the previous), denoise a small sequence to finite non-negative
// output; ONND's recurrent state is the filter's history (afnResetFilter restarts it, so the
// first frame after a reset equals the first frame of a new filter).
#include "afn_test_util.h"
#include "base/exception.h"
#include "bind_image.h"
#include "filter/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

namespace {

using afntest::bindImage;
using afntest::readBytes;

struct Frames {
    static constexpr int w = 23, h = 13;
    afn::Image color { w, h, 3 }, albedo { w, h, 3, 0.5f }, normal { w, h, 3 }, depth { w, h, 1 },
        out { w, h, 3 };

    void set(int frame)
    {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                for (int c = 0; c < 3; ++c)
                    color(x, y, c)
                        = static_cast<float>(((x * 7 + y * 3 + c + 5 * frame) % 5)) * 0.3f;
                normal(x, y, 2) = 1.0f;
                depth(x, y, 0) = 1.0f + 0.1f * static_cast<float>(x);
            }
    }
    void bindTo(afn::Filter& f)
    {
        f.setImage("color", bindImage(color));
        f.setImage("albedo", bindImage(albedo));
        f.setImage("normal", bindImage(normal));
        f.setImage("depth", bindImage(depth));
        f.setImage("output", bindImage(out));
    }
};

std::vector<float> runFrames(afn::Filter& f, Frames& fr, int first, int count)
{
    std::vector<float> last;
    for (int k = first; k < first + count; ++k) {
        fr.set(k);
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
    Frames fr;
    auto f = afn::createFilter("onnd");
    fr.bindTo(*f);
    loadParityWeights(*f, "onnd");
    f->commit(); // the valid weights survived the failed replacement
    const std::vector<float> first = runFrames(*f, fr, 0, 1);
    const std::vector<float> later = runFrames(*f, fr, 1, 2); // frames 1, 2 with state
    f->reset();
    EXPECT_EQ(runFrames(*f, fr, 0, 1), first); // a reset starts a new history
    auto g = afn::createFilter("onnd");
    fr.bindTo(*g);
    loadParityWeights(*g, "onnd");
    g->commit();
    fr.set(2);
    g->execute(); // frame 2 without the state of frames 0 and 1
    const std::vector<float> fresh(fr.out.data(), fr.out.data() + fr.out.size());
    double diff = 0.0;
    for (std::size_t i = 0; i < fresh.size(); ++i)
        diff = std::max(diff, static_cast<double>(std::fabs(fresh[i] - later[i])));
    EXPECT_GT(diff, 1e-6); // the recurrent state (and the accumulation) changed frame 2
}

TEST(BaselineFilters, MrkpDenoises)
{
    Frames fr;
    auto f = afn::createFilter("mrkp");
    fr.bindTo(*f);
    loadParityWeights(*f, "mrkp");
    f->commit();
    runFrames(*f, fr, 0, 3);
}

TEST(BaselineFilters, TypesAreRegisteredWithFeatures)
{
    for (const char* name : { "onnd", "mrkp" }) {
        const afn::FilterType* t = afn::findFilterType(name);
        ASSERT_NE(t, nullptr) << name;
        EXPECT_EQ(t->features.size(), 5u) << name;
        EXPECT_TRUE(t->stages.accumulate) << name;
    }
}
