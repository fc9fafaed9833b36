// SPDX-License-Identifier: Apache-2.0
// Determinism of the OpenFX plugin, driven by the in-process test host of tests/plugin, for every
// method the library reports: a rendered sequence is bit-identical whether the library may use one
// thread or two (oneTBB's global limit, which the plugin's device obeys), in whole frames or in
// tiles, in a fresh instance, and when two instances render at the same time from two threads.
#include "ofx_test_host.h"
#include "stress_util.h"
#include "synthetic_sequence.h"

#include <oneapi/tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

using namespace ofxhost;
using namespace ofxtest;

namespace {

const char* const kClips[][2] = { { "Albedo", "albedo" }, { "Normal", "normal" },
    { "Depth", "depth" }, { "Position", "position" }, { "Motion", "motion" } };

/// A loaded host with the general-context descriptor and a source per role.
struct PluginSession {
    PluginSession()
    {
        std::string error;
        loaded = host.load(AFN_OFX_BINARY, &error) && host.describe() == kOfxStatOK
            && host.describeInContext(kOfxImageEffectContextGeneral, general) == kOfxStatOK;
        EXPECT_TRUE(loaded) << error;
        for (const char* role : { "color", "albedo", "normal", "depth", "position", "motion" })
            sources[role] = seq.source(role);
    }
    ~PluginSession()
    {
        if (loaded)
            host.unload();
    }

    /// Every frame of the sequence rendered by a fresh instance running `method`.
    std::vector<std::vector<float>> render(const std::string& method, int tiles)
    {
        std::map<std::string, const ClipSource*> inputs = { { "Source", &sources["color"] } };
        for (const auto& c : kClips)
            inputs[c[0]] = &sources[c[1]];
        OfxStatus s = kOfxStatFailed;
        auto inst = host.createInstance(*general, kOfxImageEffectContextGeneral, inputs, &s);
        EXPECT_EQ(s, kOfxStatOK);
        const std::vector<std::string> all = stress::allMethods();
        EXPECT_EQ(host.setParam(inst.get(), "method",
                      double(std::find(all.begin(), all.end(), method) - all.begin())),
            kOfxStatOK);
        if (const std::string w = testWeightsFor(method); !w.empty())
            EXPECT_EQ(host.setParam(inst.get(), "weights", w), kOfxStatOK);
        std::vector<std::vector<float>> out;
        for (int t = seq.firstFrame; t < seq.firstFrame + seq.numFrames; ++t) {
            Frame f;
            EXPECT_EQ(host.renderFrame(inst.get(), t, 1.0, tiles, f), kOfxStatOK) << "time " << t;
            out.push_back(f.rgba);
        }
        host.destroyInstance(inst.get());
        return out;
    }

    Host host;
    bool loaded = false;
    Sequence seq;
    std::map<std::string, ClipSource> sources;
    std::unique_ptr<OfxImageEffectStruct> general;
};

void expectIdentical(const std::vector<std::vector<float>>& a,
    const std::vector<std::vector<float>>& b, const std::string& what)
{
    ASSERT_EQ(a.size(), b.size()) << what;
    for (std::size_t f = 0; f < a.size(); ++f) {
        std::string where;
        EXPECT_TRUE(stress::bitIdentical(a[f], b[f], &where))
            << what << ", frame " << f << ": " << where;
    }
}

class PluginDeterminism : public ::testing::TestWithParam<std::string> { };

TEST_P(PluginDeterminism, BitIdenticalForThreadsTilesInstancesAndConcurrentRenders)
{
    const std::string method = GetParam();
    PluginSession session;
    ASSERT_TRUE(session.loaded);
    std::vector<std::vector<float>> oneThread;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        oneThread = session.render(method, 1);
    }
    std::vector<std::vector<float>> twoThreads, concurrentA, concurrentB;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        twoThreads = session.render(method, 3);
        expectIdentical(oneThread, twoThreads, "1 thread, whole frames vs 2 threads, 3x3 tiles");
        expectIdentical(oneThread, session.render(method, 2), "a fresh instance, 2x2 tiles");
        std::thread a([&] { concurrentA = session.render(method, 1); });
        std::thread b([&] { concurrentB = session.render(method, 2); });
        a.join();
        b.join();
    }
    expectIdentical(oneThread, concurrentA, "two instances rendering at once (first)");
    expectIdentical(oneThread, concurrentB, "two instances rendering at once (second)");
    EXPECT_EQ(session.host.liveImages(), 0);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, PluginDeterminism, ::testing::ValuesIn(stress::allMethods()),
    [](const ::testing::TestParamInfo<std::string>& info) { return stress::testName(info.param); });

} // namespace
