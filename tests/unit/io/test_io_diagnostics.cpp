// SPDX-License-Identifier: Apache-2.0
// afn_io's messages: a missing role names what was tried and the file's channels, deep EXRs are
// named as such, and temporary file names never reach an error.
#include "afn/io.hpp"

#include <OpenImageIO/deepdata.h>
#include <gtest/gtest.h>

#include "test_io_util.h"

using namespace afn::io;
using afn_test::Part;
using afn_test::ScratchDir;

namespace {

std::string readError(const std::string& path, const ReadOptions& options = {})
{
    try {
        readFrame(path, options);
    } catch (const IoError& e) {
        return e.what();
    }
    return "(no error)";
}

/// A deep scanline EXR of 4x3 pixels with one R,G,B,A,Z sample each.
void writeDeepExr(const std::string& path)
{
    OIIO::ImageSpec spec(4, 3, 5, OIIO::TypeDesc::FLOAT);
    spec.channelnames = { "R", "G", "B", "A", "Z" };
    spec.alpha_channel = 3;
    spec.z_channel = 4;
    spec.deep = true;
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    OIIO::DeepData deep;
    deep.init(spec);
    for (int p = 0; p < 12; ++p) {
        deep.set_samples(p, 1);
        for (int c = 0; c < 5; ++c)
            deep.set_deep_value(p, c, 0, 0.5f);
    }
    ASSERT_TRUE(out->write_deep_image(deep)) << out->geterror();
    ASSERT_TRUE(out->close());
}

} // namespace

TEST(IoDiagnostics, MissingColourNamesTheFilesOwnChannels)
{
    ScratchDir dir;
    Part p;
    p.channels = { "N.X", "N.Y", "N.Z", "foo" };
    afn_test::writeExr(dir.file("nocolor.exr"), { p });
    const std::string what = readError(dir.file("nocolor.exr"));
    EXPECT_NE(what.find("no color channels found"), std::string::npos) << what;
    EXPECT_NE(what.find("the file has: foo, N (X,Y,Z)"), std::string::npos) << what;
    EXPECT_NE(what.find("--aov color="), std::string::npos) << what;
}

TEST(IoDiagnostics, MissingRoleListsOnlyTheNamesTried)
{
    // Blender header, Blender colour, no albedo anywhere: Blender's names and the generic ones.
    ScratchDir dir;
    Part p;
    p.channels = { "ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B" };
    afn_test::writeExr(dir.file("vl.exr"), { p });
    ReadOptions ro;
    ro.required = { Role::Color, Role::Albedo };
    const std::string what = readError(dir.file("vl.exr"), ro);
    EXPECT_NE(what.find("tried ViewLayer.Denoising Albedo; ViewLayer.DiffCol; albedo; "
                        "diffuse_albedo; the file has: ViewLayer.Combined (R,G,B)"),
        std::string::npos)
        << what;
    EXPECT_EQ(what.find("denoise_albedo"), std::string::npos) << "Arnold's names were not tried";
}

TEST(IoDiagnostics, DeepExrIsNamedAsSuch)
{
    ScratchDir dir;
    writeDeepExr(dir.file("deep.exr"));
    EXPECT_NE(readError(dir.file("deep.exr")).find("deep EXR is not supported"), std::string::npos)
        << readError(dir.file("deep.exr"));
    try {
        inspect(dir.file("deep.exr"));
        FAIL() << "inspect accepted a deep file";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("deep EXR"), std::string::npos) << e.what();
    }
}

TEST(IoDiagnostics, WriteErrorsNameTheTargetNotTheTemporaryFile)
{
    ScratchDir dir;
    const std::vector<float> px(4 * 3 * 3, 0.5f);
    try {
        writeImageAtomic(dir.file("out.nosuchformat"), 4, 3, { "R", "G", "B" }, px.data());
        FAIL() << "no error";
    } catch (const IoError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find("afn-tmp"), std::string::npos) << what;
        EXPECT_EQ(e.file(), dir.file("out.nosuchformat"));
    }
    EXPECT_TRUE(dir.list().empty());
}
