// SPDX-License-Identifier: Apache-2.0
// The BMFR dataset layout: a tiny synthetic scene folder written by the test, and
// camera_matrices.h.
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "test_io_util.h"

using namespace afn::io;
using afn_test::Part;
using afn_test::ScratchDir;

namespace {

// Two frames in the original header's shape: comments, limits, [frames][4][4], [frames][2].
const char* kHeader = R"(// Generated for a test. 1.5 is not a value: comments are ignored.
const float position_limit_squared = 0.001600;
const float normal_limit_squared = 0.250000;
/* Every matrix is multiplication of camera projection, rotation and position matrices */
const float camera_matrices[2][4][4] = {
    { // frame 0
        {0.821398, 0.958759, -0.862917, -0.862916},
        {1.0f, 2.0f, 3.0f, 4.0f},
        {5, 6, 7, 8},
        {-1e-3, 10.5, 11.25, 12.0},
    },
    { // frame 1
        {16.0, 15.0, 14.0, 13.0},
        {12.0, 11.0, 10.0, 9.0},
        {8.0, 7.0, 6.0, 5.0},
        {4.0, 3.0, 2.0, 1.0},
    },
};
const float pixel_offsets[2][2] = {
    {0.5, 0.5}, // frame 0
    {0.25, 0.75}, // frame 1
};
)";

void writeBuffer(const std::string& path, float base)
{
    Part p;
    p.channels = { "R", "G", "B" };
    p.width = 4;
    p.height = 2;
    p.value = [base](int x, int y, int c) { return base + x + 10 * y + 0.1f * c; };
    afn_test::writeExr(path, { p });
}

void makeScene(const afn_test::fs::path& inputs, int frames, bool reference)
{
    afn_test::fs::create_directories(inputs);
    std::ofstream(inputs / "camera_matrices.h") << kHeader;
    for (int n = 0; n < frames; ++n) {
        const std::string s = std::to_string(n);
        writeBuffer((inputs / ("color" + s + ".exr")).string(), 1000.0f * n + 100);
        writeBuffer((inputs / ("albedo" + s + ".exr")).string(), 1000.0f * n + 200);
        writeBuffer((inputs / ("shading_normal" + s + ".exr")).string(), 1000.0f * n + 300);
        writeBuffer((inputs / ("world_position" + s + ".exr")).string(), 1000.0f * n + 400);
        if (reference)
            writeBuffer((inputs / ("reference" + s + ".exr")).string(), 1000.0f * n + 500);
    }
}

} // namespace

TEST(IoBmfr, CameraHeaderByNamedArrays)
{
    ScratchDir dir;
    std::ofstream(dir.file("camera_matrices.h")) << kHeader;
    const std::vector<FrameCamera> cams = parseCameraMatrices(dir.file("camera_matrices.h"));
    ASSERT_EQ(cams.size(), 2u);
    EXPECT_FLOAT_EQ(cams[0].viewProjection[0], 0.821398f);
    EXPECT_FLOAT_EQ(cams[0].viewProjection[3], -0.862916f);
    EXPECT_FLOAT_EQ(cams[0].viewProjection[4], 1.0f); // row 1 starts at index 4 (row-major)
    EXPECT_FLOAT_EQ(cams[0].viewProjection[12], -1e-3f);
    EXPECT_FLOAT_EQ(cams[0].viewProjection[15], 12.0f);
    EXPECT_FLOAT_EQ(cams[1].viewProjection[0], 16.0f);
    EXPECT_FLOAT_EQ(cams[1].viewProjection[15], 1.0f);
    EXPECT_FLOAT_EQ(cams[1].pixelOffset[0], 0.25f);
    EXPECT_FLOAT_EQ(cams[1].pixelOffset[1], 0.75f);
    EXPECT_FLOAT_EQ(cams[0].positionLimitSquared, 0.0016f);
    EXPECT_FLOAT_EQ(cams[1].normalLimitSquared, 0.25f);
}

TEST(IoBmfr, MatricesOnlyHeaderFallsBack)
{
    ScratchDir dir;
    std::ofstream(dir.file("cam.h"))
        << "float camera_matrices[1][4][4] = {{{1,0,0,0},{0,1,0,0},{0,0,1,0},{0,0,0,1}}};\n";
    const auto cams = parseCameraMatrices(dir.file("cam.h"));
    ASSERT_EQ(cams.size(), 1u);
    EXPECT_EQ(cams[0].viewProjection[5], 1.0f);
    EXPECT_EQ(cams[0].pixelOffset[0], 0.5f);
    EXPECT_LT(cams[0].positionLimitSquared, 0.0f);
    std::ofstream(dir.file("bad.h")) << "const float camera_matrices[1][4][4] = {{1, 2, 3}};\n";
    EXPECT_THROW(parseCameraMatrices(dir.file("bad.h")), IoError);
    std::ofstream(dir.file("none.h")) << "const float pixel_offsets[1][2] = {{0.5, 0.5}};\n";
    EXPECT_THROW(parseCameraMatrices(dir.file("none.h")), IoError);
    EXPECT_THROW(parseCameraMatrices(dir.file("missing.h")), IoError);
}

TEST(IoBmfr, SceneFolderFrames)
{
    ScratchDir dir;
    const auto scene = dir.path() / "sponza";
    makeScene(scene / "inputs", 2, true);
    EXPECT_TRUE(isBmfrDataset(scene.string()));
    EXPECT_TRUE(isBmfrDataset((scene / "inputs").string()));
    EXPECT_FALSE(isBmfrDataset(dir.path().string()));

    ReadOptions ro;
    ro.keepAll = true;
    const FrameImages f = readFrame(bmfrFramePath(scene.string(), 1), ro);
    EXPECT_EQ(f.mapping.renderer, "bmfr");
    EXPECT_TRUE(f.mapping.tag.colorDemodulated);
    EXPECT_EQ(f.mapping.tag.normalSpace, "world");
    // Values identify the file they came from: base 1000*frame + 100 (color), 200 (albedo), ...
    const std::pair<Role, float> bases[] = { { Role::Color, 1100 }, { Role::Albedo, 1200 },
        { Role::Normal, 1300 }, { Role::Position, 1400 } };
    for (const auto& [role, base] : bases) {
        const RoleImage& img = f.roles.at(role);
        ASSERT_EQ(img.width, 4);
        ASSERT_EQ(img.height, 2);
        // pixel (x=3, y=1), channel B
        EXPECT_FLOAT_EQ(img.pixels[(1 * 4 + 3) * 3 + 2], base + 3 + 10 + 0.2f) << roleName(role);
    }
    ASSERT_TRUE(f.reference);
    EXPECT_FLOAT_EQ(f.reference->pixels[0], 1500.0f);
    ASSERT_TRUE(f.camera);
    EXPECT_FLOAT_EQ(f.camera->viewProjection[0], 16.0f);
    EXPECT_FLOAT_EQ(f.camera->pixelOffset[0], 0.25f);
    ASSERT_TRUE(f.all);
    EXPECT_EQ(f.all->channels.size(), 12u);
    EXPECT_EQ(f.all->channels[3], "albedo.R");
}

TEST(IoBmfr, MissingFrameNamesTheFile)
{
    ScratchDir dir;
    makeScene(dir.path(), 1, false);
    const FrameImages f0 = readFrame(bmfrFramePath(dir.path().string(), 0));
    EXPECT_FALSE(f0.reference);
    try {
        readFrame(bmfrFramePath(dir.path().string(), 5));
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("color5.exr"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readFrame(dir.file("nothing#bmfr:0")), IoError);
    EXPECT_THROW(readFrame(bmfrFramePath(dir.path().string(), 0) + "x"), IoError);
}
