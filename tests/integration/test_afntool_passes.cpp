// SPDX-License-Identifier: Apache-2.0
// afntool --denoise:passes= end to end on examples/passes (a Blender Cycles render with light
// passes): the denoised passes replace the noisy ones in the output, rebuild the denoised beauty
// by Blender's formula, are less noisy than the input passes, and the history names them; a file
// whose passes do not add up is warned about; bad pass names and files without passes are errors.
#include "cli_runner.h"

#include "afn/io.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

namespace {

const std::string kPasses = std::string(AFN_EXAMPLES_DIR) + "/passes/frame.####.exr";
const std::string kFrame0 = std::string(AFN_EXAMPLES_DIR) + "/passes/frame.0000.exr";

afn::io::FrameImages readPasses(const std::string& path)
{
    afn::io::ReadOptions ro;
    ro.passes = true;
    return afn::io::readFrame(path, ro);
}

/// Mean absolute difference between horizontally adjacent pixels of a pass (its grain).
double grain(const afn::io::RoleImage& p)
{
    double s = 0.0;
    long long n = 0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 1; x < p.width; ++x)
            for (int c = 0; c < 3; ++c, ++n)
                s += std::abs(p.pixels[(y * p.width + x) * p.components + c]
                    - p.pixels[(y * p.width + x - 1) * p.components + c]);
    return s / static_cast<double>(n);
}

} // namespace

TEST(AfntoolPasses, DenoisedPassesRebuildTheDenoisedBeauty)
{
    TempDir dir;
    for (const char* method : { "svgf", "afn" }) {
        const std::string out = dir.file(std::string(method) + ".####.exr");
        const CliResult r = runAfntool({ kPasses, "--frames", "0-3",
            std::string("--denoise:method=") + method + ":passes=all", "--keep-aovs", "-o", out });
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string last = dir.file(std::string(method) + ".0003.exr");
        const afn::io::FrameImages denoised = readPasses(last);
        ASSERT_EQ(denoised.passRecipe.lights.size(), 8u) << method;
        // The output's beauty (R,G,B) is the denoised one; Blender's formula over the denoised
        // passes (half floats in the file) gives it back.
        const auto rec = afn::io::recompositionOf(denoised);
        ASSERT_TRUE(rec);
        EXPECT_GT(rec->psnr, 60.0) << method;
        EXPECT_LT(rec->relativeRms, 0.005) << method;
        // Every light pass is smoother than the noisy one.
        const afn::io::FrameImages noisy
            = readPasses(std::string(AFN_EXAMPLES_DIR) + "/passes/frame.0003.exr");
        for (const char* name : { "DiffDir", "DiffInd", "GlossDir", "GlossInd" })
            EXPECT_LT(grain(denoised.passes.at(name)), 0.5 * grain(noisy.passes.at(name)))
                << method << " " << name;
        // The colour factors are copied through, not denoised.
        EXPECT_EQ(denoised.passes.at("DiffCol").pixels, noisy.passes.at("DiffCol").pixels);
        // The history says which passes were denoised.
        auto in = OIIO::ImageInput::open(last);
        ASSERT_TRUE(in);
        const std::string history = in->spec().get_string_attribute("Exif:ImageHistory");
        EXPECT_NE(
            history.find(":passes=DiffDir,DiffInd,GlossDir,GlossInd,TransDir,TransInd,Emit,Env"),
            std::string::npos)
            << history;
    }
}

TEST(AfntoolPasses, ASubsetIsDenoisedAndTheRestCopied)
{
    TempDir dir;
    const CliResult r = runAfntool({ kFrame0, "--denoise:method=ta:passes=GlossDir,Emit",
        "--keep-aovs", "-o", dir.file("o.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const afn::io::FrameImages noisy = readPasses(kFrame0);
    const afn::io::FrameImages out = readPasses(dir.file("o.exr"));
    EXPECT_EQ(out.passes.at("DiffDir").pixels, noisy.passes.at("DiffDir").pixels);
    EXPECT_NE(out.passes.at("GlossDir").pixels, noisy.passes.at("GlossDir").pixels);
}

TEST(AfntoolPasses, BadPassNamesAndFilesWithoutPassesAreErrors)
{
    TempDir dir;
    CliResult r = runAfntool(
        { kFrame0, "--denoise:method=ta:passes=GlosDir", "--keep-aovs", "-o", dir.file("o.exr") });
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("afntool ERROR: --denoise: :passes= names 'GlosDir', not a light pass"),
        std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("GlossDir"), std::string::npos) << r.err; // did you mean
    const std::string plain = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.0000.exr";
    r = runAfntool(
        { plain, "--denoise:method=ta:passes=all", "--keep-aovs", "-o", dir.file("p.exr") });
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("the file has no light passes"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty());
}

TEST(AfntoolPasses, PassesThatDoNotAddUpAreWarnedAbout)
{
    // Only the diffuse light is named as the lights: the sum falls short of Combined.
    TempDir dir;
    const CliResult r = runAfntool({ kFrame0, "--aov", "lights=DiffDir*DiffCol",
        "--denoise:method=ta:passes=all", "--keep-aovs", "-o", dir.file("o.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("the light passes do not add up to the beauty: PSNR"), std::string::npos)
        << r.err;
    const CliResult info = runAfntool({ kFrame0, "--aov", "lights=DiffDir*DiffCol", "--info" });
    EXPECT_NE(info.out.find("WARNING: the light passes do not add up"), std::string::npos)
        << info.out;
}
