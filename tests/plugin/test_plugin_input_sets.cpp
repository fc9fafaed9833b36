// SPDX-License-Identifier: Apache-2.0
// Input-aware afn through the plugin: with only some auxiliary clips connected, the
// plugin runs the model afn chooses for them (the same pixels as the C API with those inputs),
// says which in the host's log, and weights without a model for the connected clips fail the
// render with the library's message.
#include "plugin_session.h"

#include <afn/afn.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

using namespace ofxhost;
using namespace ofxtest;

namespace {

bool shippedModels()
{
    if (!afn::isFilterTypeReady("afn"))
        return false;
    for (const char* f : { "afn.afnw", "afn-color.afnw", "afn-albedo-normal.afnw" })
        if (!std::ifstream(std::string(AFN_SOURCE_DIR) + "/weights/" + f))
            return false;
    return true;
}

bool logged(const std::vector<std::string>& messages, const std::string& text)
{
    return std::any_of(messages.begin(), messages.end(),
        [&](const std::string& m) { return m.find(text) != std::string::npos; });
}

} // namespace

TEST(PluginInputSets, ConnectedClipsChooseTheModel)
{
    if (!shippedModels())
        GTEST_SKIP() << "this build does not embed the per-input-set afn weights";
    Session s;
    ASSERT_TRUE(s.loaded);
    const struct {
        std::vector<std::string> aux;
        const char* model;
    } cases[] = {
        { {}, "afn: model color, single-frame (no temporal branch: no motion or position)" },
        { { "albedo", "normal" },
            "afn: model color+albedo+normal, single-frame (no temporal branch: no motion or "
            "position)" },
        { { "albedo", "normal", "depth" },
            "afn: model color+albedo+normal+depth+temporal, single-frame (no motion or position: "
            "the temporal branch reads this frame)" },
        { kAllAux, "afn: model color+albedo+normal+depth+temporal, temporal" },
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.model);
        auto inst = s.instance("afn", c.aux);
        const auto ref = referenceFrames(s.seq, { "afn", true, 1.0, c.aux });
        for (int t : { 1, 2, 3 })
            EXPECT_TRUE(nearlyEqual(s.render(inst.get(), t), ref[t - s.seq.firstFrame])) << t;
        EXPECT_TRUE(logged(s.host.messages(), c.model));
        EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
    }
}

TEST(PluginInputSets, WeightsWithoutAModelForTheClipsFailTheRender)
{
    Session s;
    ASSERT_TRUE(s.loaded);
    auto inst = s.instance("afn", {}); // colour only
    // The full-input test archive replaces the built-in models: nothing fits colour alone.
    ASSERT_EQ(s.host.setParam(inst.get(), "weights",
                  std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw"),
        kOfxStatOK);
    Frame f;
    EXPECT_NE(s.host.renderFrame(inst.get(), 2, 1.0, 1, f), kOfxStatOK);
    const auto messages = s.host.messages();
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages.back().find("no weights for the inputs color"), std::string::npos)
        << messages.back();
    EXPECT_EQ(s.host.liveImages(), 0);
    EXPECT_EQ(s.host.destroyInstance(inst.get()), kOfxStatOK);
}
