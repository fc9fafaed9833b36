// SPDX-License-Identifier: Apache-2.0
// Role mapping from channel names alone (no files): every renderer convention, overrides, tags.
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_io_util.h"

using namespace afn::io;

namespace {

FileInfo fileWith(std::vector<std::string> channels, std::map<std::string, std::string> attrs = {})
{
    FileInfo info;
    info.path = "synthetic.exr";
    info.format = "openexr";
    SubimageInfo si;
    // Store the names sorted, as OpenEXR does, so nothing can depend on the given order.
    std::sort(channels.begin(), channels.end());
    si.channels = channels;
    si.types.assign(channels.size(), "float");
    info.subimages.push_back(si);
    info.attributes = std::move(attrs);
    return info;
}

std::vector<std::string> chans(const RoleMapping& m, Role r)
{
    const RoleChannels* rc = m.find(r);
    return rc ? rc->channels : std::vector<std::string> {};
}

using V = std::vector<std::string>;

bool contains(const std::vector<std::string>& v, const std::string& s)
{
    return std::find(v.begin(), v.end(), s) != v.end();
}

} // namespace

TEST(IoRoles, NamesRoundTrip)
{
    for (int i = 0; i < kNumRoles; ++i) {
        const Role r = static_cast<Role>(i);
        ASSERT_EQ(roleFromName(roleName(r)), r);
    }
    EXPECT_FALSE(roleFromName("nonsense"));
    EXPECT_EQ(roleComponents(Role::Motion), 2);
    EXPECT_EQ(roleComponents(Role::Depth), 1);
    EXPECT_EQ(roleComponents(Role::Normal), 3);
}

TEST(IoRoles, BlenderAllPasses)
{
    const RoleMapping m = mapRoles(fileWith(afn_test::blenderChannels("ViewLayer")));
    EXPECT_EQ(m.renderer, "blender");
    EXPECT_EQ(chans(m, Role::Color),
        (V { "ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "ViewLayer.Combined.A" }));
    EXPECT_EQ(chans(m, Role::Albedo),
        (V { "ViewLayer.Denoising Albedo.R", "ViewLayer.Denoising Albedo.G",
            "ViewLayer.Denoising Albedo.B" }));
    // World normal and planar depth are preferred over the Denoising (camera, radial) ones.
    EXPECT_EQ(chans(m, Role::Normal),
        (V { "ViewLayer.Normal.X", "ViewLayer.Normal.Y", "ViewLayer.Normal.Z" }));
    EXPECT_EQ(m.tag.normalSpace, "world");
    EXPECT_EQ(chans(m, Role::Depth), (V { "ViewLayer.Depth.Z" }));
    EXPECT_EQ(m.tag.depthKind, "planar");
    EXPECT_EQ(chans(m, Role::Position),
        (V { "ViewLayer.Position.X", "ViewLayer.Position.Y", "ViewLayer.Position.Z" }));
    EXPECT_EQ(chans(m, Role::Motion), (V { "ViewLayer.Vector.X", "ViewLayer.Vector.Y" }));
    EXPECT_EQ(m.tag.motionDirection, "to-previous");
    EXPECT_TRUE(m.tag.motionYUp);
    EXPECT_EQ(m.tag.motionUnits, "pixels");
    // Indices point at the names in the (sorted) channel list.
    const FileInfo info = fileWith(afn_test::blenderChannels("ViewLayer"));
    for (const RoleChannels& rc : m.roles)
        for (std::size_t k = 0; k < rc.channels.size(); ++k)
            EXPECT_EQ(info.subimages[0].channels[rc.indices[k]], rc.channels[k]);
}

TEST(IoRoles, BlenderDenoisingFallbacksAndDiffCol)
{
    const RoleMapping m = mapRoles(fileWith({ "VL.Combined.R", "VL.Combined.G", "VL.Combined.B",
        "VL.DiffCol.R", "VL.DiffCol.G", "VL.DiffCol.B", "VL.Denoising Normal.X",
        "VL.Denoising Normal.Y", "VL.Denoising Normal.Z", "VL.Denoising Depth.Z" }));
    EXPECT_EQ(m.renderer, "blender");
    EXPECT_EQ(chans(m, Role::Albedo), (V { "VL.DiffCol.R", "VL.DiffCol.G", "VL.DiffCol.B" }));
    EXPECT_EQ(chans(m, Role::Normal)[0], "VL.Denoising Normal.X");
    EXPECT_EQ(m.tag.normalSpace, "camera");
    EXPECT_EQ(chans(m, Role::Depth), (V { "VL.Denoising Depth.Z" }));
    EXPECT_EQ(m.tag.depthKind, "radial");
    EXPECT_FALSE(m.find(Role::Motion));
    ASSERT_TRUE(m.lookedFor.count(Role::Motion));
    EXPECT_TRUE(contains(m.lookedFor.at(Role::Motion), "VL.Vector"));
}

TEST(IoRoles, BlenderDottedViewLayerAndCompositor)
{
    std::vector<std::string> ch = afn_test::blenderChannels("shot.v2 main");
    for (const char* c : { "Composite.Combined.R", "Composite.Combined.G", "Composite.Combined.B",
             "Composite.Combined.A" })
        ch.push_back(c);
    const RoleMapping m
        = mapRoles(fileWith(ch, { { "BlenderMultiChannel", "Blender V2.55.1 and newer" } }));
    EXPECT_EQ(m.renderer, "blender");
    EXPECT_EQ(chans(m, Role::Color)[0], "shot.v2 main.Combined.R");
    EXPECT_EQ(chans(m, Role::Alpha)[0], "shot.v2 main.Combined.A");
    EXPECT_EQ(chans(m, Role::Albedo)[2], "shot.v2 main.Denoising Albedo.B");
}

TEST(IoRoles, BlenderTwoViewLayersStayTogether)
{
    std::vector<std::string> ch = afn_test::blenderChannels("A");
    for (const std::string& c : afn_test::blenderChannels("B"))
        ch.push_back(c);
    const RoleMapping m = mapRoles(fileWith(ch));
    EXPECT_EQ(chans(m, Role::Color)[0], "A.Combined.R");
    EXPECT_EQ(chans(m, Role::Normal)[0], "A.Normal.X");
    EXPECT_EQ(chans(m, Role::Motion)[0], "A.Vector.X");
}

TEST(IoRoles, TopLevelBeautyWithBlenderLayers)
{
    // What afntool -o --keep-aovs writes: beauty as R,G,B,A, the other Blender passes kept.
    std::vector<std::string> ch = { "R", "G", "B", "A" };
    for (const std::string& c : afn_test::blenderChannels("ViewLayer"))
        if (c.find(".Combined.") == std::string::npos)
            ch.push_back(c);
    const RoleMapping m = mapRoles(fileWith(ch, { { "BlenderMultiChannel", "Blender" } }));
    EXPECT_EQ(m.renderer, "blender");
    EXPECT_EQ(chans(m, Role::Color), (V { "R", "G", "B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "A" }));
    EXPECT_EQ(chans(m, Role::Albedo)[0], "ViewLayer.Denoising Albedo.R");
    EXPECT_EQ(chans(m, Role::Motion)[0], "ViewLayer.Vector.X");
}

TEST(IoRoles, Arnold)
{
    const RoleMapping m = mapRoles(fileWith({ "R", "G", "B", "A", "N.X", "N.Y", "N.Z", "P.X", "P.Y",
        "P.Z", "Z", "motionvector.X", "motionvector.Y", "diffuse_albedo.R", "diffuse_albedo.G",
        "diffuse_albedo.B", "denoise_albedo.R", "denoise_albedo.G", "denoise_albedo.B" }));
    EXPECT_EQ(m.renderer, "arnold");
    EXPECT_EQ(chans(m, Role::Color), (V { "R", "G", "B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "A" }));
    EXPECT_EQ(chans(m, Role::Albedo)[0], "denoise_albedo.R");
    EXPECT_EQ(chans(m, Role::Normal), (V { "N.X", "N.Y", "N.Z" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "Z" }));
    EXPECT_EQ(chans(m, Role::Position)[1], "P.Y");
    EXPECT_EQ(chans(m, Role::Motion), (V { "motionvector.X", "motionvector.Y" }));
    EXPECT_EQ(m.tag.normalSpace, "world");
    EXPECT_FALSE(m.warnings.empty()); // motion convention is an assumption
}

TEST(IoRoles, ArnoldUsdRgbaLayerAndAttributeHint)
{
    const RoleMapping m = mapRoles(
        fileWith({ "RGBA.R", "RGBA.G", "RGBA.B", "RGBA.A", "albedo.R", "albedo.G", "albedo.B" },
            { { "arnold/version", "7.1" } }));
    EXPECT_EQ(m.renderer, "arnold");
    EXPECT_EQ(chans(m, Role::Color), (V { "RGBA.R", "RGBA.G", "RGBA.B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "RGBA.A" }));
    EXPECT_EQ(chans(m, Role::Albedo)[0], "albedo.R");
}

TEST(IoRoles, RenderMan)
{
    const RoleMapping m = mapRoles(fileWith({ "Ci.R", "Ci.G", "Ci.B", "a", "albedo.R", "albedo.G",
        "albedo.B", "normal.R", "normal.G", "normal.B", "zfiltered.R", "forward.R", "forward.G",
        "backward.R", "backward.G", "mse.R", "mse.G", "mse.B" }));
    EXPECT_EQ(m.renderer, "renderman");
    EXPECT_EQ(chans(m, Role::Color), (V { "Ci.R", "Ci.G", "Ci.B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "a" }));
    EXPECT_EQ(chans(m, Role::Normal), (V { "normal.R", "normal.G", "normal.B" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "zfiltered.R" }));
    EXPECT_EQ(chans(m, Role::Motion), (V { "backward.R", "backward.G" }));
    EXPECT_EQ(m.tag.motionDirection, "to-previous");
    EXPECT_EQ(m.tag.normalSpace, "camera");
    EXPECT_EQ(chans(m, Role::Variance)[0], "mse.R");
}

TEST(IoRoles, RenderManForwardOnlyIsToNext)
{
    const RoleMapping m
        = mapRoles(fileWith({ "beauty.R", "beauty.G", "beauty.B", "forward.R", "forward.G" }));
    EXPECT_EQ(m.renderer, "renderman");
    EXPECT_EQ(chans(m, Role::Color)[0], "beauty.R");
    EXPECT_EQ(chans(m, Role::Motion)[0], "forward.R");
    EXPECT_EQ(m.tag.motionDirection, "to-next");
}

TEST(IoRoles, VRay)
{
    const RoleMapping m = mapRoles(
        fileWith({ "R", "G", "B", "A", "diffuse.R", "diffuse.G", "diffuse.B", "normals.X",
            "normals.Y", "normals.Z", "zDepth", "velocity.R", "velocity.G", "velocity.B" }));
    EXPECT_EQ(m.renderer, "vray");
    EXPECT_EQ(chans(m, Role::Albedo)[0], "diffuse.R");
    EXPECT_EQ(chans(m, Role::Normal)[2], "normals.Z");
    EXPECT_EQ(m.tag.normalSpace, "camera-toward-viewer");
    EXPECT_EQ(chans(m, Role::Depth), (V { "zDepth" }));
    EXPECT_EQ(chans(m, Role::Motion), (V { "velocity.R", "velocity.G" }));
    EXPECT_EQ(m.tag.motionDirection, "to-next");
}

TEST(IoRoles, Redshift)
{
    const RoleMapping m = mapRoles(
        fileWith({ "R", "G", "B", "A", "DiffuseFilter.R", "DiffuseFilter.G", "DiffuseFilter.B",
            "N.X", "N.Y", "N.Z", "Z", "P.X", "P.Y", "P.Z", "MotionVectors.R", "MotionVectors.G" }));
    EXPECT_EQ(m.renderer, "redshift");
    EXPECT_EQ(chans(m, Role::Albedo)[0], "DiffuseFilter.R");
    EXPECT_EQ(chans(m, Role::Motion), (V { "MotionVectors.R", "MotionVectors.G" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "Z" }));
}

TEST(IoRoles, Karma)
{
    const RoleMapping m
        = mapRoles(fileWith({ "C.R", "C.G", "C.B", "C.A", "albedo.R", "albedo.G", "albedo.B", "N.X",
            "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "depth.Z", "motionvector.X", "motionvector.Y" }));
    EXPECT_EQ(m.renderer, "karma");
    EXPECT_EQ(chans(m, Role::Color), (V { "C.R", "C.G", "C.B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "C.A" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "depth.Z" }));
    EXPECT_EQ(chans(m, Role::Motion)[0], "motionvector.X");
}

TEST(IoRoles, GenericRgbOnly)
{
    const RoleMapping m = mapRoles(fileWith({ "R", "G", "B", "A" }));
    EXPECT_EQ(m.renderer, "generic");
    EXPECT_EQ(chans(m, Role::Color), (V { "R", "G", "B" }));
    EXPECT_EQ(chans(m, Role::Alpha), (V { "A" }));
    EXPECT_FALSE(m.find(Role::Albedo));
    EXPECT_TRUE(contains(m.lookedFor.at(Role::Albedo), "albedo"));
}

TEST(IoRoles, NoColourListsWhatWasLookedFor)
{
    const RoleMapping m = mapRoles(fileWith({ "foo.X", "bar" }));
    EXPECT_FALSE(m.find(Role::Color));
    const auto& looked = m.lookedFor.at(Role::Color);
    EXPECT_TRUE(contains(looked, "R,G,B"));
    EXPECT_TRUE(contains(looked, "Ci")); // no preset found a colour: every preset was tried
    EXPECT_TRUE(contains(looked, "Combined"));
}

TEST(IoRoles, MultiPartLayersFromPartNames)
{
    FileInfo info;
    info.path = "multi.exr";
    SubimageInfo beauty, albedo, normal;
    beauty.name = "rgba";
    beauty.channels = { "A", "B", "G", "R" };
    albedo.name = "albedo";
    albedo.channels = { "B", "G", "R" };
    normal.name = "other";
    normal.channels = { "N.X", "N.Y", "N.Z" };
    info.subimages = { beauty, albedo, normal };
    const RoleMapping m = mapRoles(info);
    const RoleChannels* c = m.find(Role::Color);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->subimage, 0);
    EXPECT_EQ(c->indices, (std::vector<int> { 3, 2, 1 }));
    const RoleChannels* a = m.find(Role::Albedo);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->subimage, 1);
    EXPECT_EQ(a->channels, (V { "R", "G", "B" }));
    const RoleChannels* n = m.find(Role::Normal);
    ASSERT_TRUE(n);
    EXPECT_EQ(n->subimage, 2);
    EXPECT_EQ(n->indices, (std::vector<int> { 0, 1, 2 }));
}

TEST(IoRoles, MultiPartBeautyNotFirst)
{
    FileInfo info;
    SubimageInfo albedo, beauty;
    albedo.name = "albedo";
    albedo.channels = { "R", "G", "B" };
    beauty.name = "beauty";
    beauty.channels = { "R", "G", "B", "A" };
    info.subimages = { albedo, beauty };
    const RoleMapping m = mapRoles(info);
    ASSERT_TRUE(m.find(Role::Color));
    EXPECT_EQ(m.find(Role::Color)->subimage, 1);
    ASSERT_TRUE(m.find(Role::Albedo));
    EXPECT_EQ(m.find(Role::Albedo)->subimage, 0);
    EXPECT_EQ(m.find(Role::Alpha)->subimage, 1);
}

TEST(IoRoles, OverridesChannelsLayersAndTags)
{
    MappingOverrides o;
    parseOverride("albedo=mydiff", o); // layer prefix
    parseOverride("normal=nx, ny ,nz", o); // explicit channels, spaces trimmed
    parseOverride("depth=dist", o); // one channel
    parseOverride("normal.space=camera-toward-viewer", o);
    parseOverride("motion.yUp=false", o);
    const RoleMapping m = mapRoles(fileWith({ "R", "G", "B", "mydiff.R", "mydiff.G", "mydiff.B",
                                       "nx", "ny", "nz", "dist", "N.X", "N.Y", "N.Z" }),
        o);
    EXPECT_EQ(chans(m, Role::Albedo), (V { "mydiff.R", "mydiff.G", "mydiff.B" }));
    EXPECT_EQ(chans(m, Role::Normal), (V { "nx", "ny", "nz" }));
    EXPECT_EQ(chans(m, Role::Depth), (V { "dist" }));
    EXPECT_EQ(m.tag.normalSpace, "camera-toward-viewer");
    EXPECT_FALSE(m.tag.motionYUp);
    EXPECT_EQ(m.find(Role::Albedo)->source, "--aov albedo=mydiff");
}

TEST(IoRoles, OverrideOfMissingChannelsIsAnError)
{
    // No silent fallback to the automatic choice, and no run without the role asked for.
    MappingOverrides o;
    parseOverride("albedo=nope.R,nope.G,nope.B", o);
    try {
        mapRoles(fileWith({ "R", "G", "B", "albedo.R", "albedo.G", "albedo.B" }), o);
        FAIL() << "no error";
    } catch (const IoError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("--aov albedo=nope.R,nope.G,nope.B"), std::string::npos) << what;
        EXPECT_NE(what.find("the file has: B, G, R, albedo (B,G,R)"), std::string::npos) << what;
    }
}

TEST(IoRoles, OverrideColourOnBlenderFile)
{
    MappingOverrides o;
    parseOverride("color=ViewLayer.Denoising Albedo", o);
    const RoleMapping m = mapRoles(fileWith(afn_test::blenderChannels("ViewLayer")), o);
    EXPECT_EQ(chans(m, Role::Color)[0], "ViewLayer.Denoising Albedo.R");
}

TEST(IoRoles, OverrideToAKnownPassKeepsItsConventions)
{
    MappingOverrides o;
    parseOverride("normal=ViewLayer.Denoising Normal", o);
    parseOverride("depth=ViewLayer.Denoising Depth.Z", o);
    const RoleMapping m = mapRoles(fileWith(afn_test::blenderChannels("ViewLayer")), o);
    EXPECT_EQ(chans(m, Role::Normal)[0], "ViewLayer.Denoising Normal.X");
    EXPECT_EQ(m.tag.normalSpace, "camera");
    EXPECT_EQ(chans(m, Role::Depth), (V { "ViewLayer.Denoising Depth.Z" }));
    EXPECT_EQ(m.tag.depthKind, "radial");
    parseOverride("normal.space=world", o); // explicit tags win
    EXPECT_EQ(
        mapRoles(fileWith(afn_test::blenderChannels("ViewLayer")), o).tag.normalSpace, "world");
}

TEST(IoRoles, ParseOverrideErrors)
{
    MappingOverrides o;
    EXPECT_THROW(parseOverride("noequals", o), IoError);
    EXPECT_THROW(parseOverride("flavour=R,G,B", o), IoError);
    EXPECT_THROW(parseOverride("normal=a,b", o), IoError);
    EXPECT_THROW(parseOverride("normal.space=sideways", o), IoError);
    EXPECT_THROW(parseOverride("motion.yUp=maybe", o), IoError);
    EXPECT_THROW(parseOverride("albedo=a,,b", o), IoError);
    EXPECT_THROW(parseOverride("albedo=", o), IoError);
    EXPECT_TRUE(o.channels.empty());
    EXPECT_TRUE(o.tags.empty());
}
