// SPDX-License-Identifier: Apache-2.0
// Atomic writes: round trips (half/float per channel, 8-bit PNG), refusals and clean failure.
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "test_io_util.h"

using namespace afn::io;
using afn_test::ScratchDir;

namespace {

std::vector<float> ramp(int n)
{
    std::vector<float> v(n);
    // 1/3 steps: not exactly representable in half, exactly representable... nowhere, good.
    for (int i = 0; i < n; ++i)
        v[i] = static_cast<float>(i) / 3.0f;
    return v;
}

} // namespace

TEST(IoWrite, HalfAndFloatPerChannelRoundTrip)
{
    ScratchDir dir;
    const std::string path = dir.file("out.exr");
    const int w = 5, h = 4, nch = 4;
    const std::vector<float> px = ramp(w * h * nch);
    writeImageAtomic(
        path, w, h, { "R", "G", "B", "Z" }, px.data(), {}, { "half", "half", "half", "float" });
    const FileInfo info = inspect(path);
    EXPECT_EQ(
        info.subimages[0].types, (std::vector<std::string> { "half", "half", "half", "float" }));
    EXPECT_EQ(info.subimages[0].compression, "zip");
    ReadOptions ro;
    ro.keepAll = true;
    const FrameImages f = readFrame(path, ro);
    const LayeredImage& all = *f.all;
    ASSERT_EQ(all.channels, (std::vector<std::string> { "R", "G", "B", "Z" }));
    for (int i = 0; i < w * h; ++i) {
        for (int c = 0; c < 3; ++c) // half: 11 significant bits
            EXPECT_NEAR(
                all.pixels[i * 4 + c], px[i * 4 + c], std::abs(px[i * 4 + c]) * 1e-3f + 1e-6f);
        EXPECT_EQ(all.pixels[i * 4 + 3], px[i * 4 + 3]); // float: exact
    }
    EXPECT_EQ(dir.list(), (std::vector<std::string> { "out.exr" })); // no temporary left
}

TEST(IoWrite, FloatDataTypeIsExactAndCompressionChosen)
{
    ScratchDir dir;
    const std::string path = dir.file("f.exr");
    const std::vector<float> px = ramp(3 * 2 * 3);
    WriteOptions wo;
    wo.dataType = "float";
    wo.compression = "piz";
    wo.attributes["Frame"] = "12";
    writeImageAtomic(path, 3, 2, { "R", "G", "B" }, px.data(), wo);
    const FileInfo info = inspect(path);
    EXPECT_EQ(info.subimages[0].types[0], "float");
    EXPECT_EQ(info.subimages[0].compression, "piz");
    EXPECT_EQ(info.attributes.at("Frame"), "12");
    const FrameImages f = readFrame(path);
    EXPECT_EQ(f.roles.at(Role::Color).pixels, px);
}

TEST(IoWrite, PngIsClampedTo8Bit)
{
    ScratchDir dir;
    const std::string path = dir.file("p.png");
    const std::vector<float> px = { 2.0f, -1.0f, 0.5f, 0.0f, 1.0f, 0.25f };
    writeImageAtomic(path, 2, 1, { "R", "G", "B" }, px.data());
    const FileInfo info = inspect(path);
    EXPECT_EQ(info.format, "png");
    const FrameImages f = readFrame(path);
    const std::vector<float>& got = f.roles.at(Role::Color).pixels;
    const float expect[] = { 1.0f, 0.0f, 128.0f / 255.0f, 0.0f, 1.0f, 64.0f / 255.0f };
    for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(got[i], expect[i], 1e-6f) << i;
    // TIFF goes the same 8-bit way.
    const std::string tif = dir.file("t.tif");
    writeImageAtomic(tif, 2, 1, { "R", "G", "B" }, px.data());
    EXPECT_EQ(inspect(tif).subimages[0].types[0], "uint8");
    const std::vector<float> t = readFrame(tif).roles.at(Role::Color).pixels;
    for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(t[i], expect[i], 1e-6f) << i;
}

TEST(IoWrite, RefusesToOverwriteAnInput)
{
    ScratchDir dir;
    const std::string path = dir.file("in.exr");
    std::ofstream(path) << "original";
    const float px[3] = { 1, 2, 3 };
    WriteOptions wo;
    wo.inputs = { dir.file("./sub/../in.exr") };
    afn_test::fs::create_directories(dir.path() / "sub");
    EXPECT_THROW(writeImageAtomic(path, 1, 1, { "R", "G", "B" }, px, wo), IoError);
    std::ifstream in(path);
    std::string content;
    in >> content;
    EXPECT_EQ(content, "original");
    EXPECT_TRUE(samePath(path, dir.file("sub/../in.exr")));
    EXPECT_FALSE(samePath(path, dir.file("other.exr")));
}

TEST(IoWrite, MissingOutputDirectory)
{
    ScratchDir dir;
    const float px[3] = { 1, 2, 3 };
    try {
        writeImageAtomic(dir.file("nodir/out.exr"), 1, 1, { "R", "G", "B" }, px);
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), dir.file("nodir/out.exr"));
    }
    std::ofstream(dir.file("afile")) << "x"; // parent is a file, not a directory
    EXPECT_THROW(writeImageAtomic(dir.file("afile/out.exr"), 1, 1, { "R", "G", "B" }, px), IoError);
}

TEST(IoWrite, ReadOnlyDirectory)
{
    ScratchDir dir;
    const float px[3] = { 1, 2, 3 };
    if (::geteuid() == 0)
        GTEST_SKIP() << "running as root: permissions are not enforced";
    afn_test::fs::create_directories(dir.path() / "ro");
    afn_test::fs::permissions(
        dir.path() / "ro", afn_test::fs::perms::owner_read | afn_test::fs::perms::owner_exec);
    try {
        writeImageAtomic(dir.file("ro/out.exr"), 1, 1, { "R", "G", "B" }, px);
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("not writable"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(afn_test::fs::is_empty(dir.path() / "ro"));
}

TEST(IoWrite, FailureLeavesNothingBehind)
{
    ScratchDir dir;
    const std::vector<float> px(2 * 2 * 6, 0.5f);
    const std::vector<std::string> six = { "R", "G", "B", "A", "X", "Y" };
    // Unknown extension: no writer.
    EXPECT_THROW(writeImageAtomic(dir.file("out.nosuchformat"), 2, 2, six, px.data()), IoError);
    // JPEG cannot hold 6 channels.
    try {
        writeImageAtomic(dir.file("out.jpg"), 2, 2, six, px.data());
    } catch (const IoError&) {
    }
    // Bad arguments.
    EXPECT_THROW(writeImageAtomic(dir.file("out.exr"), 0, 2, six, px.data()), IoError);
    EXPECT_THROW(
        writeImageAtomic(dir.file("out.exr"), 2, 2, six, px.data(), {}, { "half" }), IoError);
    EXPECT_THROW(writeImageAtomic(dir.file("out.exr"), 2, 2, six, px.data(), {},
                     std::vector<std::string>(6, "int")),
        IoError);
    for (const std::string& name : dir.list())
        EXPECT_EQ(name.find("afn-tmp"), std::string::npos) << name;
    EXPECT_FALSE(afn_test::fs::exists(dir.file("out.exr")));
}

TEST(IoWrite, ReplacesExistingOutput)
{
    ScratchDir dir;
    const std::string path = dir.file("o.exr");
    const float a[3] = { 1, 1, 1 }, b[3] = { 2, 2, 2 };
    writeImageAtomic(path, 1, 1, { "R", "G", "B" }, a);
    writeImageAtomic(path, 1, 1, { "R", "G", "B" }, b);
    EXPECT_EQ(readFrame(path).roles.at(Role::Color).pixels[0], 2.0f);
    EXPECT_EQ(dir.list().size(), 1u);
}
