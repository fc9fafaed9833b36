// SPDX-License-Identifier: Apache-2.0
// afntool's outputs are faithful to their input: data and display windows, header
// metadata, integer bit depths, colour encodings by output type, and a record of what made them
// (Software, Exif:ImageHistory with the method and every parameter, the colour space).
#include "cli_runner.h"
#include "image_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace {

/// A linear half EXR of grey `value` with a region-render (or overscan) data window.
OIIO::ImageSpec regionSpec(int x, int y, int w, int h, int fullW, int fullH)
{
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeHalf);
    spec.x = x;
    spec.y = y;
    spec.full_x = spec.full_y = 0;
    spec.full_width = fullW;
    spec.full_height = fullH;
    return spec;
}

void expectWindows(const OIIO::ImageSpec& s, int x, int y, int w, int h, int fullW, int fullH)
{
    EXPECT_EQ(s.x, x);
    EXPECT_EQ(s.y, y);
    EXPECT_EQ(s.width, w);
    EXPECT_EQ(s.height, h);
    EXPECT_EQ(s.full_x, 0);
    EXPECT_EQ(s.full_y, 0);
    EXPECT_EQ(s.full_width, fullW);
    EXPECT_EQ(s.full_height, fullH);
}

TEST(AfntoolOutputs, RegionRenderAndOverscanKeepTheirWindows)
{
    TempDir dir;
    const std::string region = dir.file("region.exr"), over = dir.file("overscan.exr");
    ASSERT_TRUE(writeImage(
        region, regionSpec(50, 40, 200, 100, 320, 180), std::vector<float>(200 * 100 * 3, 0.5f)));
    ASSERT_TRUE(writeImage(
        over, regionSpec(-16, -8, 352, 196, 320, 180), std::vector<float>(352 * 196 * 3, 0.25f)));

    CliResult r = runAfntool({ region, "--denoise:method=identity", "-o", dir.file("r.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectWindows(readImage(dir.file("r.exr")).spec, 50, 40, 200, 100, 320, 180);
    r = runAfntool({ over, "-o", dir.file("o.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectWindows(readImage(dir.file("o.exr")).spec, -16, -8, 352, 196, 320, 180);

    // A PNG has no windows: the display window is written (oiiotool's autocrop, Nuke's Write),
    // the region in place and black around it.
    r = runAfntool({ region, "-o", dir.file("r.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ReadBack png = readImage(dir.file("r.png"));
    expectWindows(png.spec, 0, 0, 320, 180, 320, 180);
    ASSERT_EQ(png.pixels.size(), 320u * 180 * 3);
    auto at = [&](int x, int y) { return png.pixels[(static_cast<size_t>(y) * 320 + x) * 3]; };
    EXPECT_EQ(at(0, 0), 0.0f);
    EXPECT_EQ(at(49, 40), 0.0f);
    EXPECT_NEAR(srgbToLinear(at(50, 40)), 0.5f, 0.01f);
    EXPECT_NEAR(srgbToLinear(at(249, 139)), 0.5f, 0.01f);
    EXPECT_EQ(at(250, 139), 0.0f);
}

TEST(AfntoolOutputs, HeaderMetadataIsKeptAndTheRunIsRecorded)
{
    TempDir dir;
    const std::string in = dir.file("in.exr");
    OIIO::ImageSpec spec(16, 8, 3, OIIO::TypeFloat);
    const float world[16] = { 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16 };
    spec.attribute("worldToCamera", OIIO::TypeMatrix, world);
    spec.attribute("Frame", "12");
    spec.attribute("Scene", "Scene");
    spec.attribute("RenderTime", "00:01.93");
    spec.attribute("cycles.ViewLayer.samples", "16");
    spec.attribute("renderer:seed", 42);
    spec.attribute("Exif:ImageHistory", "blender render");
    ASSERT_TRUE(writeImage(in, spec, std::vector<float>(16 * 8 * 3, 0.3f)));

    const CliResult r = runAfntool({ in, "--denoise:method=svgf:sigmaL=3", "-o",
        dir.file("out.exr"), "--preview", dir.file("p.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const OIIO::ImageSpec out = readImage(dir.file("out.exr")).spec;
    const OIIO::ParamValue* m = out.find_attribute("worldToCamera", OIIO::TypeMatrix);
    ASSERT_NE(m, nullptr);
    for (int i = 0; i < 16; ++i)
        EXPECT_EQ(static_cast<const float*>(m->data())[i], world[i]) << i;
    EXPECT_EQ(out.get_string_attribute("Frame"), "12");
    EXPECT_EQ(out.get_string_attribute("Scene"), "Scene");
    EXPECT_EQ(out.get_string_attribute("RenderTime"), "00:01.93");
    EXPECT_EQ(out.get_string_attribute("cycles.ViewLayer.samples"), "16");
    EXPECT_EQ(out.get_int_attribute("renderer:seed"), 42);
    // (OIIO's string_view::rfind differs from std::string's: compare std::strings.)
    EXPECT_EQ(std::string(out.get_string_attribute("Software")).rfind("afntool ", 0), 0u);
    const std::string history(out.get_string_attribute("Exif:ImageHistory"));
    EXPECT_EQ(history.rfind("blender render\nafntool ", 0), 0u) << history;
    // The method with the given and the default parameters, and the output.
    for (const char* part : { "--denoise:method=svgf",
             ":sigmaL=3:", ":iterations=5:", ":alpha=0.2:", ":normal.space=world", "-o " })
        EXPECT_NE(history.find(part), std::string::npos) << part << " in " << history;

    const OIIO::ImageSpec preview = readImage(dir.file("p.png")).spec;
    EXPECT_EQ(std::string(preview.get_string_attribute("Software")).rfind("afntool ", 0), 0u);
    EXPECT_NE(std::string(preview.get_string_attribute("Exif:ImageHistory")).find("--preview"),
        std::string::npos);
}

TEST(AfntoolOutputs, IntegerBitDepthsAreKept)
{
    TempDir dir;
    const std::string tif = dir.file("in16.tif");
    std::vector<float> px(8 * 4 * 3);
    for (size_t i = 0; i < px.size(); ++i)
        px[i] = float(i * 997 % 65536) / 65535.0f;
    ASSERT_TRUE(writeImage(tif, OIIO::ImageSpec(8, 4, 3, OIIO::TypeUInt16), px));

    CliResult r = runAfntool({ tif, "-o", dir.file("out.tif"), "-o", dir.file("out.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* name : { "out.tif", "out.png" }) {
        const ReadBack back = readImage(dir.file(name));
        EXPECT_EQ(back.spec.format, OIIO::TypeUInt16) << name;
        ASSERT_EQ(back.pixels.size(), px.size()) << name;
        for (size_t i = 0; i < px.size(); ++i)
            ASSERT_NEAR(back.pixels[i], px[i], 0.5f / 65535.0f) << name << " value " << i;
    }
    r = runAfntool({ tif, "-d", "uint8", "-o", dir.file("out8.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readImage(dir.file("out8.png")).spec.format, OIIO::TypeUInt8);
    r = runAfntool({ tif, "-d", "float", "-o", dir.file("f.tif") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readImage(dir.file("f.tif")).spec.format, OIIO::TypeFloat);
    r = runAfntool({ tif, "-d", "uint16", "-o", dir.file("x.exr") });
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("afntool ERROR: -d uint16 cannot be stored in openexr files (valid: "
                         "half, float)"),
        std::string::npos)
        << r.err;
    EXPECT_FALSE(std::ifstream(dir.file("x.exr")).good());
}

TEST(AfntoolOutputs, ColourEncodingFollowsTheOutputType)
{
    TempDir dir;
    // An 8-bit PNG holds sRGB-encoded values: EXR outputs get them linearised.
    const std::string png = dir.file("in.png");
    ASSERT_TRUE(writeImage(png, OIIO::ImageSpec(4, 2, 3, OIIO::TypeUInt8),
        std::vector<float>(4 * 2 * 3, 188.0f / 255.0f)));
    CliResult r = runAfntool({ png, "-o", dir.file("lin.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ReadBack lin = readImage(dir.file("lin.exr"));
    ASSERT_FALSE(lin.pixels.empty());
    EXPECT_NEAR(lin.pixels[0], srgbToLinear(188.0f / 255.0f), 2e-3f);
    EXPECT_EQ(lin.spec.get_string_attribute("colorInteropID"), "lin_rec709_scene");

    // A linear EXR written as 8- or 16-bit integers is display-referred (sRGB-encoded).
    const std::string exr = dir.file("in.exr");
    ASSERT_TRUE(writeImage(
        exr, OIIO::ImageSpec(4, 2, 3, OIIO::TypeFloat), std::vector<float>(4 * 2 * 3, 0.5f)));
    r = runAfntool({ exr, "-o", dir.file("d8.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runAfntool({ exr, "-d", "uint16", "-o", dir.file("d16.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readImage(dir.file("d8.png")).spec.format, OIIO::TypeUInt8);
    EXPECT_EQ(readImage(dir.file("d16.png")).spec.format, OIIO::TypeUInt16);
    for (const char* name : { "d8.png", "d16.png" }) {
        const ReadBack d = readImage(dir.file(name));
        ASSERT_FALSE(d.pixels.empty()) << name;
        EXPECT_NEAR(srgbToLinear(d.pixels[0]), 0.5f, 4e-3f) << name << " holds " << d.pixels[0];
    }
}

TEST(AfntoolOutputs, OutColorSpaceIsConvertedAndRecorded)
{
    TempDir dir;
    const std::string in = dir.file("red.exr");
    std::vector<float> red(4 * 2 * 3, 0.0f);
    for (size_t i = 0; i < red.size(); i += 3)
        red[i] = 1.0f;
    ASSERT_TRUE(writeImage(in, OIIO::ImageSpec(4, 2, 3, OIIO::TypeFloat), red));
    CliResult r = runAfntool({ in, "--outcolorspace", "ACEScg", "-o", dir.file("aces.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ReadBack aces = readImage(dir.file("aces.exr"));
    EXPECT_EQ(aces.spec.get_string_attribute("colorInteropID"), "lin_ap1_scene");
    const OIIO::ParamValue* chroma = aces.spec.find_attribute("chromaticities");
    ASSERT_NE(chroma, nullptr);
    EXPECT_NEAR(static_cast<const float*>(chroma->data())[0], 0.713f, 1e-6f); // AP1 red x
    // Rec.709 red in AP1 (the Rec.709 -> ACEScg matrix's first column).
    EXPECT_NEAR(aces.pixels[0], 0.6131f, 2e-3f);
    EXPECT_NEAR(aces.pixels[1], 0.0701f, 2e-3f);
    EXPECT_NEAR(aces.pixels[2], 0.0206f, 2e-3f);
    // Read back, the tag is honoured: converted to Linear Rec.709 it is pure red again.
    r = runAfntool(
        { dir.file("aces.exr"), "--outcolorspace", "lin_rec709", "-o", dir.file("back.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ReadBack back = readImage(dir.file("back.exr"));
    EXPECT_NEAR(back.pixels[0], 1.0f, 2e-3f);
    EXPECT_NEAR(back.pixels[1], 0.0f, 2e-3f);
    EXPECT_EQ(back.spec.get_string_attribute("colorInteropID"), "lin_rec709_scene");
}

} // namespace
