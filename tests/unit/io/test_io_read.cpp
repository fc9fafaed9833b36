// SPDX-License-Identifier: Apache-2.0
// Reading frames from synthetic EXRs written by the tests, error paths, and the committed Blender
// file.
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "test_io_util.h"

using namespace afn::io;
using afn_test::Part;
using afn_test::ScratchDir;

namespace {

/// The value the default Part generator puts in channel c (index in the list given) at (x, y).
float expected(int x, int y, int c)
{
    return static_cast<float>(100 * c + 10 * y + x);
}

int indexOf(const std::vector<std::string>& v, const std::string& s)
{
    for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i] == s)
            return static_cast<int>(i);
    return -1;
}

std::string messageOf(const std::function<void()>& f, std::string* file = nullptr)
{
    try {
        f();
    } catch (const IoError& e) {
        if (file)
            *file = e.file();
        return e.what();
    }
    return "(no IoError)";
}

} // namespace

TEST(IoRead, BlenderLikeChannelsByName)
{
    ScratchDir dir;
    Part p;
    p.channels = afn_test::blenderChannels("ViewLayer");
    p.types.assign(p.channels.size(), "float");
    for (int c = 0; c < 4; ++c)
        p.types[c] = "half"; // Combined is half, as Blender writes it
    p.attributes = { { "BlenderMultiChannel", "Blender V2.55.1 and newer" }, { "Frame", "7" } };
    const std::string path = dir.file("bl.exr");
    afn_test::writeExr(path, { p });

    ReadOptions ro;
    ro.keepAll = true;
    const FrameImages f = readFrame(path, ro);
    EXPECT_EQ(f.mapping.renderer, "blender");
    for (Role r :
        { Role::Color, Role::Albedo, Role::Normal, Role::Depth, Role::Position, Role::Motion })
        ASSERT_TRUE(f.roles.count(r)) << roleName(r);
    // Each role component equals the value written for that name, wherever the file stored it.
    auto check = [&](Role r, const std::vector<std::string>& names) {
        const RoleImage& img = f.roles.at(r);
        ASSERT_EQ(img.components, static_cast<int>(names.size()));
        ASSERT_EQ(img.width, 4);
        ASSERT_EQ(img.height, 3);
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x)
                for (std::size_t k = 0; k < names.size(); ++k)
                    EXPECT_EQ(img.pixels[(y * 4 + x) * names.size() + k],
                        expected(x, y, indexOf(p.channels, "ViewLayer." + names[k])))
                        << names[k];
    };
    check(Role::Color, { "Combined.R", "Combined.G", "Combined.B" });
    check(Role::Alpha, { "Combined.A" });
    check(Role::Normal, { "Normal.X", "Normal.Y", "Normal.Z" });
    check(Role::Depth, { "Depth.Z" });
    check(Role::Motion, { "Vector.X", "Vector.Y" });
    // Motion is non-zero: no motion-blur warning.
    for (const std::string& w : f.mapping.warnings)
        EXPECT_EQ(w.find("all zero"), std::string::npos);

    ASSERT_TRUE(f.all);
    EXPECT_EQ(f.all->channels.size(), p.channels.size());
    const int combR = indexOf(f.all->channels, "ViewLayer.Combined.R");
    const int vecW = indexOf(f.all->channels, "ViewLayer.Vector.W");
    ASSERT_GE(combR, 0);
    ASSERT_GE(vecW, 0);
    EXPECT_EQ(f.all->types[combR], "half");
    EXPECT_EQ(f.all->types[vecW], "float");
    EXPECT_EQ(f.all->pixels[(1 * 4 + 2) * f.all->channels.size() + vecW],
        expected(2, 1, indexOf(p.channels, "ViewLayer.Vector.W")));
    EXPECT_EQ(f.all->attributes.at("Frame"), "7");
    EXPECT_EQ(f.all->compression, "zip");
}

TEST(IoRead, BlenderZeroVectorWarns)
{
    ScratchDir dir;
    Part p;
    p.channels = afn_test::blenderChannels("ViewLayer");
    const std::vector<std::string> names = p.channels;
    p.value = [names](int x, int y, int c) {
        return names[c].find("Vector") != std::string::npos ? 0.0f : 1.0f;
    };
    const std::string path = dir.file("blur.exr");
    afn_test::writeExr(path, { p });
    const FrameImages f = readFrame(path);
    bool warned = false;
    for (const std::string& w : f.mapping.warnings)
        warned |= w.find("all zero") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(IoRead, MultiPartFile)
{
    ScratchDir dir;
    Part beauty, albedo, normal;
    beauty.name = "rgba";
    beauty.channels = { "R", "G", "B", "A" };
    beauty.types = { "half", "half", "half", "half" };
    albedo.name = "albedo";
    albedo.channels = { "R", "G", "B" };
    albedo.value = [](int x, int y, int c) { return 0.25f * (c + 1); };
    normal.name = "normals";
    normal.channels = { "N.X", "N.Y", "N.Z" };
    normal.value = [](int x, int y, int c) { return c == 2 ? 1.0f : 0.0f; };
    const std::string path = dir.file("multi.exr");
    afn_test::writeExr(path, { beauty, albedo, normal });

    const FileInfo info = inspect(path);
    ASSERT_EQ(info.subimages.size(), 3u);
    EXPECT_EQ(info.subimages[1].name, "albedo");
    EXPECT_EQ(info.subimages[0].types[0], "half");

    ReadOptions ro;
    ro.keepAll = true;
    const FrameImages f = readFrame(path, ro);
    EXPECT_EQ(f.mapping.find(Role::Albedo)->subimage, 1);
    const RoleImage& a = f.roles.at(Role::Albedo);
    EXPECT_EQ(a.pixels[0], 0.25f);
    EXPECT_EQ(a.pixels[1], 0.5f);
    EXPECT_EQ(a.pixels[2], 0.75f);
    const RoleImage& n = f.roles.at(Role::Normal);
    EXPECT_EQ(n.pixels[2], 1.0f);
    const RoleImage& c = f.roles.at(Role::Color);
    EXPECT_EQ(c.pixels[(2 * 4 + 3) * 3 + 1], expected(3, 2, 1)); // G at (3, 2)
    ASSERT_TRUE(f.all);
    EXPECT_EQ(f.all->channels,
        (std::vector<std::string> { "R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B",
            "normals.N.X", "normals.N.Y", "normals.N.Z" }));
}

TEST(IoRead, DataWindowDiffersFromDisplayWindow)
{
    ScratchDir dir;
    Part p;
    p.channels = { "R", "G", "B" };
    p.x = 2;
    p.y = 1;
    p.width = 3;
    p.height = 2;
    p.fullWidth = 8;
    p.fullHeight = 6;
    const std::string path = dir.file("crop.exr");
    afn_test::writeExr(path, { p });
    const FileInfo info = inspect(path);
    EXPECT_EQ(info.subimages[0].dataWindow.x, 2);
    EXPECT_EQ(info.subimages[0].dataWindow.width, 3);
    EXPECT_EQ(info.subimages[0].displayWindow.width, 8);
    EXPECT_EQ(info.subimages[0].displayWindow.height, 6);
    ReadOptions ro;
    ro.keepAll = true;
    const FrameImages f = readFrame(path, ro);
    const RoleImage& c = f.roles.at(Role::Color);
    EXPECT_EQ(c.width, 3);
    EXPECT_EQ(c.height, 2);
    EXPECT_EQ(c.pixels[(1 * 3 + 2) * 3 + 0], expected(2, 1, 0)); // data-window pixel (2, 1)
    EXPECT_EQ(f.all->dataWindow.y, 1);
    EXPECT_EQ(f.all->displayWindow.width, 8);
}

TEST(IoRead, MissingFile)
{
    ScratchDir dir;
    std::string file;
    const std::string msg = messageOf([&] { readFrame(dir.file("nope.exr")); }, &file);
    EXPECT_NE(msg.find("not found"), std::string::npos) << msg;
    EXPECT_EQ(file, dir.file("nope.exr"));
    EXPECT_THROW(inspect(dir.file("nope.exr")), IoError);
    EXPECT_THROW(readFrame(dir.path().string()), IoError); // a directory
}

TEST(IoRead, UnreadableFile)
{
    ScratchDir dir;
    const std::string path = dir.file("junk.exr");
    std::ofstream(path) << "this is not an image";
    std::string file;
    messageOf([&] { readFrame(path); }, &file);
    EXPECT_EQ(file, path);
    EXPECT_THROW(inspect(path), IoError);
}

TEST(IoRead, TruncatedExr)
{
    ScratchDir dir;
    Part p;
    p.channels = { "R", "G", "B" };
    p.width = 64;
    p.height = 64;
    p.value
        = [](int x, int y, int c) { return std::sin(0.37f * x + 1.3f * y + c); }; // incompressible
    const std::string path = dir.file("cut.exr");
    afn_test::writeExr(path, { p });
    const auto size = afn_test::fs::file_size(path);
    afn_test::fs::resize_file(path, size * 2 / 3);
    std::string file;
    const std::string msg = messageOf([&] { readFrame(path); }, &file);
    EXPECT_NE(msg, "(no IoError)");
    EXPECT_EQ(file, path);
}

TEST(IoRead, NoColourChannelsNamesWhatWasLookedFor)
{
    ScratchDir dir;
    Part p;
    p.channels = { "depth.Z", "aaa.X" }; // stored sorted: depth.Z is the second channel
    const std::string path = dir.file("nocolor.exr");
    afn_test::writeExr(path, { p });
    std::string file;
    const std::string msg = messageOf([&] { readFrame(path); }, &file);
    EXPECT_NE(msg.find("no color channels"), std::string::npos) << msg;
    EXPECT_NE(msg.find("R,G,B"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Combined"), std::string::npos) << msg;
    EXPECT_NE(msg.find("the file has: aaa (X), depth (Z)"), std::string::npos) << msg;
    EXPECT_EQ(file, path);
    // Not required -> no error, and depth is still read.
    ReadOptions ro;
    ro.required = {};
    const FrameImages f = readFrame(path, ro);
    ASSERT_TRUE(f.roles.count(Role::Depth));
    EXPECT_EQ(f.mapping.find(Role::Depth)->indices, (std::vector<int> { 1 }));
    const RoleImage& d = f.roles.at(Role::Depth);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(d.pixels[y * 4 + x], expected(x, y, 0)); // depth.Z was given first
}

TEST(IoRead, RequiredRoleMissingNamesOverride)
{
    ScratchDir dir;
    Part p;
    p.channels = { "R", "G", "B" };
    const std::string path = dir.file("rgb.exr");
    afn_test::writeExr(path, { p });
    ReadOptions ro;
    parseOverride("albedo=diff.R,diff.G,diff.B", ro.overrides);
    ro.required = { Role::Color, Role::Albedo };
    const std::string msg = messageOf([&] { readFrame(path, ro); });
    // An override naming channels the file lacks is an error of its own, required or not.
    EXPECT_NE(msg.find("--aov albedo=diff.R,diff.G,diff.B: no such channels"), std::string::npos)
        << msg;
    ro.required = {};
    EXPECT_NE(messageOf([&] { readFrame(path, ro); }).find("no such channels"), std::string::npos);
}

TEST(IoStats, SmallExactCase)
{
    RoleImage img { 2, 2, 1, { -1.0f, 3.0f, NAN, INFINITY } };
    RoleStats s = computeStats(img);
    EXPECT_EQ(s.count, 4);
    EXPECT_EQ(s.nan, 1);
    EXPECT_EQ(s.inf, 1);
    EXPECT_EQ(s.negative, 1);
    EXPECT_EQ(s.min, -1.0);
    EXPECT_EQ(s.max, 3.0);
    EXPECT_EQ(s.mean, 1.0);
    const RoleStats empty = computeStats(RoleImage { 1, 1, 1, { NAN } });
    EXPECT_EQ(empty.mean, 0.0);
    EXPECT_EQ(empty.nan, 1);
}

TEST(IoRead, CommittedBlenderFile)
{
    const std::string path = std::string(AFN_TEST_DATA) + "/blender_64x36.exr";
    if (!afn_test::fs::exists(path))
        GTEST_SKIP() << "no " << path;
    const FrameImages f = readFrame(path);
    EXPECT_EQ(f.mapping.renderer, "blender");
    const std::pair<Role, const char*> expect[] = {
        { Role::Color, "ViewLayer.Combined.R" },
        { Role::Albedo, "ViewLayer.Denoising Albedo.R" },
        { Role::Normal, "ViewLayer.Normal.X" },
        { Role::Depth, "ViewLayer.Depth.Z" },
        { Role::Position, "ViewLayer.Position.X" },
        { Role::Motion, "ViewLayer.Vector.X" },
        { Role::Alpha, "ViewLayer.Combined.A" },
    };
    for (const auto& [role, first] : expect) {
        const RoleChannels* rc = f.mapping.find(role);
        ASSERT_TRUE(rc) << roleName(role);
        EXPECT_EQ(rc->channels.front(), first);
        const RoleImage& img = f.roles.at(role);
        EXPECT_EQ(img.width, 64);
        EXPECT_EQ(img.height, 36);
    }
    EXPECT_EQ(f.mapping.tag.normalSpace, "world");
    EXPECT_EQ(f.mapping.tag.depthKind, "planar");
    EXPECT_TRUE(f.mapping.tag.motionYUp);
    // Physical sanity: world normals are unit length on geometry; the sky has depth 1e10.
    const RoleImage& n = f.roles.at(Role::Normal);
    const RoleImage& d = f.roles.at(Role::Depth);
    // Pixels on silhouettes average geometry and sky samples (length 0.25, 0.5, 0.75 at 4 spp),
    // so only most geometry pixels hold unit normals; none may be longer than 1.
    int geometry = 0, sky = 0, unit = 0;
    for (int i = 0; i < 64 * 36; ++i) {
        if (d.pixels[i] > 1e9f) {
            ++sky;
            continue;
        }
        ++geometry;
        const float* v = &n.pixels[i * 3];
        const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        EXPECT_LT(len, 1.02f);
        unit += std::abs(len - 1.0f) < 0.02f;
    }
    EXPECT_GT(sky, 0);
    EXPECT_GT(geometry, 0);
    EXPECT_GT(unit, geometry * 8 / 10);
    // Motion blur was off: the Vector pass is not all zero, and no warning was raised.
    const RoleStats ms = computeStats(f.roles.at(Role::Motion));
    EXPECT_GT(std::max(std::abs(ms.min), std::abs(ms.max)), 0.0);
    for (const std::string& w : f.mapping.warnings)
        EXPECT_EQ(w.find("all zero"), std::string::npos);
}

TEST(IoRead, SamplesPerPixelFromTheBlenderHeader)
{
    ScratchDir dir;
    Part p;
    p.channels = afn_test::blenderChannels("ViewLayer");
    p.attributes = { { "cycles.ViewLayer.samples", "16" }, { "cycles.ViewLayer.total_time", "1" } };
    afn_test::writeExr(dir.file("bl.exr"), { p });
    EXPECT_EQ(readFrame(dir.file("bl.exr")).samples, std::optional<int>(16));

    p.attributes = {};
    afn_test::writeExr(dir.file("none.exr"), { p });
    EXPECT_FALSE(readFrame(dir.file("none.exr")).samples.has_value());

    FileInfo info; // two view layers: the colour's wins; otherwise ambiguous
    info.attributes = { { "cycles.Back.samples", "4" }, { "cycles.ViewLayer.samples", "64" } };
    EXPECT_EQ(samplesPerPixel(info, "ViewLayer.Combined.R"), std::optional<int>(64));
    EXPECT_EQ(samplesPerPixel(info, "Back.Combined.R"), std::optional<int>(4));
    EXPECT_FALSE(samplesPerPixel(info).has_value());
    info.attributes = { { "cycles.ViewLayer.samples", "1" } }; // one layer: any colour channel
    EXPECT_EQ(samplesPerPixel(info, "R"), std::optional<int>(1));
    for (const char* bad : { "", "abc", "16x", "0", "-3" }) {
        info.attributes = { { "cycles.ViewLayer.samples", bad } };
        EXPECT_FALSE(samplesPerPixel(info).has_value()) << bad;
    }
}
