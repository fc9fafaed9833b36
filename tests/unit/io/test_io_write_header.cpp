// SPDX-License-Identifier: Apache-2.0
// What a write keeps and checks: windows, typed metadata read back from a frame's header, and
// data types / compressions against the format (OutputFormat).
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include "test_io_util.h"

using namespace afn::io;
using afn_test::ScratchDir;

TEST(IoWriteHeader, WindowsAndTypedMetadataRoundTrip)
{
    ScratchDir dir;
    const std::string in = dir.file("in.exr"), out = dir.file("out.exr");
    OIIO::ImageSpec spec(3, 2, 3, OIIO::TypeFloat);
    spec.x = 5;
    spec.y = -1;
    spec.full_width = 10;
    spec.full_height = 4;
    const float m[16] = { 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 3, 0, 4, 5, 6, 1 };
    spec.attribute("worldToCamera", OIIO::TypeMatrix, m);
    spec.attribute("Frame", "3");
    const std::vector<float> px(3 * 2 * 3, 0.5f);
    auto o = OIIO::ImageOutput::create(in);
    ASSERT_TRUE(o && o->open(in, spec) && o->write_image(OIIO::TypeFloat, px.data()) && o->close());

    const FrameImages f = readFrame(in);
    EXPECT_EQ(f.header.format, "openexr");
    EXPECT_EQ(f.header.dataWindow.x, 5);
    EXPECT_EQ(f.header.dataWindow.y, -1);
    EXPECT_EQ(f.header.displayWindow.width, 10);
    EXPECT_EQ(f.header.colorType, "float");
    WriteOptions wo;
    wo.metadata = f.header.attributes;
    wo.dataWindow = f.header.dataWindow;
    wo.displayWindow = f.header.displayWindow;
    writeImageAtomic(out, 3, 2, { "R", "G", "B" }, px.data(), wo);
    auto back = OIIO::ImageInput::open(out);
    ASSERT_TRUE(back);
    const OIIO::ImageSpec& s = back->spec();
    EXPECT_EQ(s.x, 5);
    EXPECT_EQ(s.y, -1);
    EXPECT_EQ(s.full_width, 10);
    EXPECT_EQ(s.full_height, 4);
    EXPECT_EQ(std::string(s.get_string_attribute("Frame")), "3");
    const OIIO::ParamValue* p = s.find_attribute("worldToCamera", OIIO::TypeMatrix);
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(static_cast<const float*>(p->data())[13], 5.0f);

    // A PNG has no windows: the display window, data in place, 0 around it.
    writeImageAtomic(dir.file("out.png"), 3, 2, { "R", "G", "B" }, px.data(), wo);
    const FrameImages png = readFrame(dir.file("out.png"));
    const RoleImage& c = png.roles.at(Role::Color);
    ASSERT_EQ(c.width, 10);
    ASSERT_EQ(c.height, 4);
    EXPECT_EQ(c.pixels[(0 * 10 + 5) * 3], 128.0f / 255.0f); // data row y=0 is its second row
    EXPECT_EQ(c.pixels[(1 * 10 + 5) * 3], 0.0f); // below the data window
    EXPECT_EQ(c.pixels[(0 * 10 + 4) * 3], 0.0f); // left of it
}

TEST(IoWriteHeader, TypesAndCompressionAreCheckedAgainstTheFormat)
{
    ScratchDir dir;
    EXPECT_EQ(outputFormat(dir.file("a.exr")).storedType("uint8"), "half");
    EXPECT_EQ(outputFormat(dir.file("a.exr")).storedType("uint16"), "float");
    EXPECT_EQ(outputFormat(dir.file("a.png")).storedType("half"), "uint8");
    EXPECT_EQ(outputFormat(dir.file("a.png")).storedType("uint16"), "uint16");
    EXPECT_EQ(outputFormat(dir.file("a.jpg")).storedType("uint16"), "uint8");
    EXPECT_TRUE(outputFormat(dir.file("a.exr")).acceptsCompression("dwaa:45"));
    EXPECT_FALSE(outputFormat(dir.file("a.exr")).acceptsCompression("lzma"));
    const float px[3] = { 0.1f, 0.2f, 0.3f };
    WriteOptions wo;
    wo.compression = "lzma";
    try {
        writeImageAtomic(dir.file("o.exr"), 1, 1, { "R", "G", "B" }, px, wo);
        FAIL() << "lzma accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("valid: none, rle, zips, zip, piz"), std::string::npos)
            << e.what();
    }
    wo.compression.clear();
    wo.dataType = "uint16";
    EXPECT_THROW(writeImageAtomic(dir.file("o.exr"), 1, 1, { "R", "G", "B" }, px, wo), IoError);
    writeImageAtomic(dir.file("o.png"), 1, 1, { "R", "G", "B" }, px, wo);
    EXPECT_EQ(inspect(dir.file("o.png")).subimages[0].types[0], "uint16");
    EXPECT_TRUE(dir.list().size() == 1u) << "nothing left by the refused writes";
}
