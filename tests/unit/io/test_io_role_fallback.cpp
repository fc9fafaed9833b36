// SPDX-License-Identifier: Apache-2.0
// Role detection falls back to the generic names after the chosen (e.g. header-hinted) preset, and
// reports only the names it tried.
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace afn::io;

namespace {

using V = std::vector<std::string>;

FileInfo fileWith(std::vector<std::string> channels, std::map<std::string, std::string> attrs = {})
{
    FileInfo info;
    info.path = "synthetic.exr";
    info.format = "openexr";
    SubimageInfo si;
    std::sort(channels.begin(), channels.end()); // as OpenEXR stores them
    si.channels = channels;
    si.types.assign(channels.size(), "float");
    info.subimages.push_back(si);
    info.attributes = std::move(attrs);
    return info;
}

V chans(const RoleMapping& m, Role r)
{
    const RoleChannels* rc = m.find(r);
    return rc ? rc->channels : V {};
}

const V kGenericAovs = { "R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y",
    "N.Z", "P.X", "P.Y", "P.Z", "Z", "motionvector.X", "motionvector.Y" };

const std::map<std::string, std::string> kBlenderHints
    = { { "BlenderMultiChannel", "Blender V2.55.1 and newer" },
          { "cycles.ViewLayer.samples", "4" } };

} // namespace

TEST(IoRoleFallback, HintedBlenderFileWithGenericNamesMapsEveryAov)
{
    const RoleMapping m = mapRoles(fileWith(kGenericAovs, kBlenderHints));
    EXPECT_EQ(m.renderer, "blender"); // the header decides the preset and its conventions
    EXPECT_EQ(chans(m, Role::Color), (V { "R", "G", "B" }));
    EXPECT_EQ(chans(m, Role::Albedo), (V { "albedo.R", "albedo.G", "albedo.B" }));
    EXPECT_EQ(chans(m, Role::Normal), (V { "N.X", "N.Y", "N.Z" }));
    EXPECT_EQ(chans(m, Role::Position), (V { "P.X", "P.Y", "P.Z" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "Z" }));
    EXPECT_EQ(chans(m, Role::Motion), (V { "motionvector.X", "motionvector.Y" }));
    EXPECT_EQ(m.presetsTried, (V { "Blender Cycles", "generic" }));
    EXPECT_NE(m.find(Role::Albedo)->source.find("generic"), std::string::npos);
    // The conventions of generic names are Blender's, and the user is told so.
    EXPECT_TRUE(m.tag.motionYUp);
    bool told = false;
    for (const std::string& w : m.warnings)
        told = told
            || (w.find("generic channel names") != std::string::npos
                && w.find("normal.space=world") != std::string::npos
                && w.find("motion.yUp=true") != std::string::npos);
    EXPECT_TRUE(told) << ::testing::PrintToString(m.warnings);
}

TEST(IoRoleFallback, PresetNamesWinOverGenericOnes)
{
    V ch = { "VL.Combined.R", "VL.Combined.G", "VL.Combined.B", "VL.DiffCol.R", "VL.DiffCol.G",
        "VL.DiffCol.B", "albedo.R", "albedo.G", "albedo.B" };
    const RoleMapping m = mapRoles(fileWith(ch, kBlenderHints));
    EXPECT_EQ(chans(m, Role::Albedo)[0], "VL.DiffCol.R");
    for (const std::string& w : m.warnings)
        EXPECT_EQ(w.find("generic channel names"), std::string::npos) << w;
}

TEST(IoRoleFallback, LookedForListsOnlyTheNamesTried)
{
    // A Blender file without albedo: Blender's names (with the view layer) then the generic ones;
    // nothing from Arnold, RenderMan, V-Ray, ... which were not applied.
    const RoleMapping m = mapRoles(
        fileWith({ "VL.Combined.R", "VL.Combined.G", "VL.Combined.B", "VL.Combined.A" }));
    EXPECT_EQ(m.renderer, "blender");
    EXPECT_EQ(m.lookedFor.at(Role::Albedo),
        (V { "VL.Denoising Albedo", "VL.DiffCol", "albedo", "diffuse_albedo" }));
    for (const auto& [role, names] : m.lookedFor)
        for (const std::string& n : names)
            for (const char* other : { "denoise_albedo", "DiffuseFilter", "normals", "zDepth" })
                EXPECT_EQ(n.find(other), std::string::npos) << roleName(role) << ": " << n;
}

TEST(IoRoleFallback, ChannelsAreNotTakenTwice)
{
    // Blender's colour is top-level R,G,B; the generic fallback must not also use them (e.g. a
    // generic normal spelled R,G,B under a layer is fine, top-level channels of the colour are
    // not).
    const RoleMapping m = mapRoles(fileWith({ "R", "G", "B", "A", "Z" }, kBlenderHints));
    EXPECT_EQ(chans(m, Role::Color), (V { "R", "G", "B" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "Z" }));
    std::vector<int> used;
    for (const RoleChannels& rc : m.roles)
        for (int i : rc.indices) {
            EXPECT_EQ(std::count(used.begin(), used.end(), i), 0) << roleName(rc.role);
            used.push_back(i);
        }
}
