// SPDX-License-Identifier: Apache-2.0
// The plugin over the bundled Blender example sequence (examples/sequence) against afntool's
// output for the same frames and method: whole frames in order, then tiles out of order.
#include "ofx_test_host.h"

#include <afn/afn.hpp>
#include <afn/io.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;
using afn::io::Role;
using namespace ofxhost;

namespace {

constexpr int kFrames = 3;
const std::string kPattern = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.####.exr";

/// One role of every frame as a host clip source (scale 1 only: afntool has no proxy mode).
struct RoleClip {
    std::vector<std::vector<float>> frames;
    ClipSource source;
};

/// Build a clip source from `role` of every frame, padded to `components` (extra channels 0, or
/// for colour the alpha role / 1).
bool makeClip(const std::vector<afn::io::FrameImages>& in, Role role, int components, RoleClip& out)
{
    for (const auto& f : in) {
        auto it = f.roles.find(role);
        if (it == f.roles.end())
            return false;
        const afn::io::RoleImage& r = it->second;
        auto alpha = f.roles.find(Role::Alpha);
        std::vector<float> px(size_t(r.width) * r.height * components, 0.0f);
        for (size_t i = 0, n = size_t(r.width) * r.height; i < n; ++i) {
            for (int c = 0; c < std::min(components, r.components); ++c)
                px[i * components + c] = r.pixels[i * r.components + c];
            if (role == Role::Color && components == 4)
                px[i * 4 + 3] = alpha == f.roles.end() ? 1.0f : alpha->second.pixels[i];
        }
        out.frames.push_back(std::move(px));
        out.source.width = r.width;
        out.source.height = r.height;
    }
    out.source.components = components;
    out.source.firstFrame = 0;
    out.source.lastFrame = kFrames - 1;
    const auto* frames = &out.frames;
    out.source.frame = [frames](double t, double scale, std::vector<float>& px) {
        const int k = int(t);
        if (scale != 1.0 || k != t || k < 0 || k >= int(frames->size()))
            return false;
        px = (*frames)[k];
        return true;
    };
    return true;
}

/// Index of the option whose id is `v` (an option's label starts with its id: "SVGF (...)").
int choiceIndex(const OfxImageEffectStruct& inst, const std::string& param, const std::string& v)
{
    const auto& options = inst.params.find(param)->props.getStrings(kOfxParamPropChoiceOption);
    for (size_t i = 0; i < options.size(); ++i) {
        std::string id = options[i].substr(0, options[i].find(' '));
        std::transform(id.begin(), id.end(), id.begin(), ::tolower);
        if (id == v)
            return int(i);
    }
    return int(options.size());
}

} // namespace

TEST(PluginExample, MatchesAfntoolOnTheExampleSequence)
{
    if (!fs::exists(afn::io::expandFramePattern(kPattern, 0)))
        GTEST_SKIP() << "examples/sequence is not there";
    std::vector<afn::io::FrameImages> frames;
    for (int f = 0; f < kFrames; ++f)
        frames.push_back(afn::io::readFrame(afn::io::expandFramePattern(kPattern, f)));
    const afn::io::SpaceTag tag = frames[0].mapping.tag;
    ASSERT_TRUE(tag.motionYUp) << "Blender motion is y up, as OFX pixel vectors";

    const std::pair<Role, const char*> aux[]
        = { { Role::Albedo, "Albedo" }, { Role::Normal, "Normal" }, { Role::Depth, "Depth" },
              { Role::Position, "Position" }, { Role::Motion, "Motion" } };
    std::map<std::string, RoleClip> clips;
    ASSERT_TRUE(makeClip(frames, Role::Color, 4, clips["Source"]));
    for (const auto& [role, name] : aux)
        if (!makeClip(frames, role,
                role == Role::Depth        ? 1
                    : role == Role::Motion ? 4
                                           : 3,
                clips[name]))
            clips.erase(name);
    std::map<std::string, const ClipSource*> inputs;
    for (auto& [name, c] : clips)
        inputs[name] = &c.source;

    Host host(Layout { true, 1 });
    std::string error;
    ASSERT_TRUE(host.load(AFN_OFX_BINARY, &error)) << error;
    ASSERT_EQ(host.describe(), kOfxStatOK);
    std::unique_ptr<OfxImageEffectStruct> general;
    ASSERT_EQ(host.describeInContext(kOfxImageEffectContextGeneral, general), kOfxStatOK);

    const fs::path out = fs::path(AFN_BINARY_DIR) / "plugin_example_out";
    fs::create_directories(out);
    const std::vector<std::string> types = afn::filterTypes();
    int compared = 0;
    for (const std::string m : { "afn", "svgf", "ta", "bmfr", "wskpn", "nbgd", "onnd", "mrkp" }) {
        if (std::find(types.begin(), types.end(), m) == types.end())
            continue;
        if (!afn::isFilterTypeReady(m.c_str()))
            continue; // this build ships no weights for it: the plugin cannot run it

        SCOPED_TRACE("method " + m);
        const std::string outPattern = (out / (m + ".####.exr")).string();
        const std::string cmd = std::string("'") + AFNTOOL_PATH + "' -q --frames 0-"
            + std::to_string(kFrames - 1) + " '" + kPattern + "' --denoise:method=" + m
            + " -d float -o '" + outPattern + "'";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

        OfxStatus st = kOfxStatFailed;
        auto inst = host.createInstance(*general, kOfxImageEffectContextGeneral, inputs, &st);
        ASSERT_EQ(st, kOfxStatOK);
        ASSERT_EQ(host.setParam(inst.get(), "method", choiceIndex(*inst, "method", m)), kOfxStatOK);
        // The file's conventions, as afntool takes them from the role mapping.
        ASSERT_EQ(host.setParam(inst.get(), "normal_space",
                      choiceIndex(*inst, "normal_space", tag.normalSpace)),
            kOfxStatOK);
        ASSERT_EQ(host.setParam(
                      inst.get(), "depth_kind", choiceIndex(*inst, "depth_kind", tag.depthKind)),
            kOfxStatOK);
        ASSERT_EQ(host.setParam(inst.get(), "motion_direction",
                      choiceIndex(*inst, "motion_direction", tag.motionDirection)),
            kOfxStatOK);
        ASSERT_EQ(host.setParam(inst.get(), "motion_units",
                      choiceIndex(*inst, "motion_units", tag.motionUnits)),
            kOfxStatOK);
        ASSERT_EQ(host.setParam(inst.get(), "color_demodulated", tag.colorDemodulated ? 1 : 0),
            kOfxStatOK);

        auto compare = [&](int t, int tiles) {
            Frame f;
            ASSERT_EQ(host.renderFrame(inst.get(), t, 1.0, tiles, f), kOfxStatOK);
            const afn::io::FrameImages ref
                = afn::io::readFrame(afn::io::expandFramePattern(outPattern, t));
            const afn::io::RoleImage& r = ref.roles.at(Role::Color);
            ASSERT_EQ(size_t(r.width) * r.height * 4, f.rgba.size());
            size_t bad = 0;
            double worst = 0;
            for (size_t i = 0, n = size_t(r.width) * r.height; i < n; ++i)
                for (int c = 0; c < 3; ++c) {
                    const double a = f.rgba[i * 4 + c], b = r.pixels[i * r.components + c];
                    const double err = std::abs(a - b) / std::max(std::abs(b), 1e-3);
                    worst = std::max(worst, std::isnan(a) ? 1e30 : err);
                    bad += !(err <= 1e-5);
                }
            EXPECT_EQ(bad, 0u) << "frame " << t << " tiles " << tiles << ": worst relative error "
                               << worst;
        };
        for (int t = 0; t < kFrames; ++t)
            compare(t, 1);
        for (int t : { 1, 0, 2 })
            compare(t, 2);
        EXPECT_EQ(host.destroyInstance(inst.get()), kOfxStatOK);
        ++compared;
        std::printf("compared %s over %d frames with afntool\n", m.c_str(), kFrames);
    }
    EXPECT_EQ(host.unload(), kOfxStatOK);
    if (compared == 0)
        GTEST_SKIP() << "no temporal method in this build";
}
