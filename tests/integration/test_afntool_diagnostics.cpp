// SPDX-License-Identifier: Apache-2.0
// afntool's diagnostics end to end: role detection with generic names after a hinted preset,
// warnings when a method runs without the AOVs it uses, strict checks with "did you mean",
// messages that name the user's files, short help, usage, progress lines and the summary.
#include "cli_runner.h"

#include "afn/io.hpp"

#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const std::string kSequence = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.####.exr";
const std::string kFrame0 = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.0000.exr";

void expectCleanError(const CliResult& r, const std::string& needle)
{
    EXPECT_NE(r.exitCode, 0);
    EXPECT_LT(r.exitCode, 128) << "killed by a signal";
    EXPECT_EQ(r.err.rfind("afntool ERROR: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
}

/// A small float EXR with the given channels (channel c = c + 0.25) and header attributes.
void writeExr(const std::string& path, const std::vector<std::string>& channels,
    const std::map<std::string, std::string>& attributes = {})
{
    const int w = 8, h = 6;
    std::vector<float> px(static_cast<size_t>(w) * h * channels.size());
    for (size_t i = 0; i < px.size(); ++i)
        px[i] = float(i % channels.size()) * 0.1f + 0.25f;
    afn::io::WriteOptions wo;
    wo.dataType = "float";
    wo.attributes = attributes;
    afn::io::writeImageAtomic(path, w, h, channels, px.data(), wo);
}

const std::vector<std::string> kGenericAovs = { "R", "G", "B", "A", "albedo.R", "albedo.G",
    "albedo.B", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "Z", "motionvector.X", "motionvector.Y" };
const std::map<std::string, std::string> kBlenderHeader
    = { { "BlenderMultiChannel", "Blender V2.55.1 and newer" } };

int countOf(const std::string& text, const std::string& needle)
{
    int n = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
        ++n;
    return n;
}

} // namespace

// ---- A: role detection and missing AOVs ---------------------------------------------------------

TEST(AfntoolDiagnostics, BlenderHeaderWithGenericNamesMapsEveryAov)
{
    TempDir dir;
    writeExr(dir.file("generic.exr"), kGenericAovs, kBlenderHeader);
    const CliResult r = runAfntool({ "--info", "--json", dir.file("generic.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\"renderer\": \"blender\""), std::string::npos) << r.out;
    for (const char* role : { "\"albedo\": [\"albedo.R\"", "\"normal\": [\"N.X\"",
             "\"position\": [\"P.X\"", "\"depth\": [\"Z\"]", "\"motion\": [\"motionvector.X\"" })
        EXPECT_NE(r.out.find(role), std::string::npos) << role << "\n" << r.out;
    EXPECT_NE(r.out.find("\"presetsTried\": [\"Blender Cycles\", \"generic\"]"), std::string::npos)
        << r.out;
}

TEST(AfntoolDiagnostics, MissingRoleReportsOnlyWhatWasTried)
{
    TempDir dir;
    writeExr(dir.file("vl.exr"),
        { "ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
            "ViewLayer.Combined.A" });
    const CliResult r = runAfntool({ "--info", dir.file("vl.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("albedo    (not found; looked for ViewLayer.Denoising Albedo, "
                         "ViewLayer.DiffCol, albedo, diffuse_albedo)\n"),
        std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("roles (Blender Cycles names, then generic names):"), std::string::npos)
        << r.out;
    for (const char* other : { "denoise_albedo", "DiffuseFilter", "zDepth", "MotionVectors" })
        EXPECT_EQ(r.out.find(other), std::string::npos) << other << " was never tried\n" << r.out;
    // One short line per missing role; the file's own channels are listed.
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);)
        if (line.find("not found") != std::string::npos)
            EXPECT_LT(line.size(), 120u) << line;
    EXPECT_NE(r.out.find("ViewLayer.Combined.R (float)"), std::string::npos) << r.out;

    // A file without colour: the error lists the file's channels.
    writeExr(dir.file("nocolor.exr"), { "N.X", "N.Y", "N.Z" });
    const CliResult e = runAfntool({ dir.file("nocolor.exr"), "-o", dir.file("o.exr") });
    expectCleanError(e, "the file has: N (X,Y,Z)");
}

TEST(AfntoolDiagnostics, MethodsWithoutTheirAovsWarn)
{
    TempDir dir;
    for (const char* f : { "plain.0000.exr", "plain.0001.exr" })
        writeExr(dir.file(f), { "R", "G", "B" });
    const std::string in = dir.file("plain.####.exr");
    for (const char* method : { "svgf", "bmfr" }) {
        const CliResult r = runAfntool({ "-v", "--frames", "0-1", in,
            std::string("--denoise:method=") + method, "-o", dir.file("out.####.exr") });
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(countOf(r.err,
                      "afntool WARNING: --denoise: " + std::string(method)
                          + " runs without albedo (demodulation"),
            1)
            << r.err;
        EXPECT_NE(r.err.find("normal ("), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("motion or position with a camera (reprojection"), std::string::npos)
            << r.err;
        // With -v the log names them for every frame.
        EXPECT_NE(r.err.find(std::string(method) + " without albedo, normal, "), std::string::npos)
            << r.err;
        EXPECT_EQ(countOf(r.err, std::string(method) + " without albedo"), 2) << r.err;
    }
    // With every AOV there is nothing to warn about.
    const CliResult full = runAfntool(
        { "--frames", "0-1", kSequence, "--denoise:method=svgf", "-o", dir.file("full.####.exr") });
    ASSERT_EQ(full.exitCode, 0) << full.err;
    EXPECT_EQ(full.err.find("runs without"), std::string::npos) << full.err;
    EXPECT_EQ(full.err.find("svgf without"), std::string::npos) << full.err;
    // identity reads no AOVs.
    const CliResult id = runAfntool(
        { "--frames", "0-1", in, "--denoise:method=identity", "-o", dir.file("id.####.exr") });
    ASSERT_EQ(id.exitCode, 0) << id.err;
    EXPECT_EQ(id.err.find("WARNING"), std::string::npos) << id.err;
}

// ---- B: strict checks, suggestions, messages
// -----------------------------------------------------

TEST(AfntoolDiagnostics, UnknownModifiersOfPreviewAndContactSheetAreRejected)
{
    TempDir dir;
    CliResult r = runAfntool({ kFrame0, "--preview:vew=Standard", dir.file("p.png") });
    expectCleanError(r, "--preview: unknown modifier 'vew' (did you mean 'view'?)");
    r = runAfntool({ kFrame0, "--contact-sheet:colums=2", dir.file("c.png") });
    expectCleanError(r, "--contact-sheet: unknown modifier 'colums' (did you mean 'columns'?)");
    EXPECT_NE(r.err.find("known: display, view, columns, tilesize"), std::string::npos) << r.err;
    expectCleanError(runAfntool({ kFrame0, "--info:json" }), "--info: unknown modifier 'json'");
    EXPECT_TRUE(dir.entries().empty());
}

TEST(AfntoolDiagnostics, NearMatchSuggestions)
{
    TempDir dir;
    const std::string out = dir.file("o.exr");
    expectCleanError(runAfntool({ "--framse", "0-1", kSequence }), "did you mean '--frames'?");
    expectCleanError(runAfntool({ kFrame0, "--denoise:method=svfg", "-o", out }),
        "unknown method 'svfg' (did you mean 'svgf'?)");
    const CliResult p = runAfntool({ kFrame0, "--denoise:method=svgf:sigmal=4", "-o", out });
    expectCleanError(p, "svgf has no parameter 'sigmal' (did you mean 'sigmaL'?)");
    const CliResult aov = runAfntool({ "--aov", "albedoo=diffuse", kFrame0, "--info" });
    expectCleanError(aov, "unknown role 'albedoo' (did you mean 'albedo'?)");
    EXPECT_EQ(countOf(aov.err, "--aov"), 1) << aov.err;
    EXPECT_NE(aov.err.find("roles: color, albedo, normal, depth, position, motion, alpha"),
        std::string::npos)
        << aov.err;
    expectCleanError(runAfntool({ "--aov", "normal.spce=camera", kFrame0, "--info" }),
        "did you mean 'normal.space'?");
    EXPECT_FALSE(fs::exists(out));
}

TEST(AfntoolDiagnostics, AovNamingMissingChannelsIsAnError)
{
    TempDir dir;
    const CliResult r
        = runAfntool({ "--aov", "albedo=nope.R,nope.G,nope.B", kFrame0, "-o", dir.file("o.exr") });
    expectCleanError(r, "--aov albedo=nope.R,nope.G,nope.B: no such channels or layer");
    EXPECT_NE(r.err.find("ViewLayer.Denoising Albedo (R,G,B)"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty());
}

TEST(AfntoolDiagnostics, ErrorsNameTheOutputNotTheTemporaryFile)
{
    TempDir dir;
    const CliResult r = runAfntool({ kFrame0, "-o", dir.file("out.xyz") });
    expectCleanError(r, "out.xyz");
    EXPECT_EQ(r.err.find("afn-tmp"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty());
}

TEST(AfntoolDiagnostics, DeepExrIsNamed)
{
    TempDir dir;
    const std::string path = dir.file("deep.exr");
    OIIO::ImageSpec spec(4, 3, 5, OIIO::TypeDesc::FLOAT);
    spec.channelnames = { "R", "G", "B", "A", "Z" };
    spec.alpha_channel = 3;
    spec.z_channel = 4;
    spec.deep = true;
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec));
    OIIO::DeepData deep;
    deep.init(spec);
    for (int p = 0; p < 12; ++p)
        deep.set_samples(p, 1);
    ASSERT_TRUE(out->write_deep_image(deep));
    ASSERT_TRUE(out->close());
    const CliResult r = runAfntool({ path, "-o", dir.file("o.exr") });
    expectCleanError(r, "deep EXR is not supported");
    EXPECT_EQ(r.err.find("corrupt"), std::string::npos) << r.err;
}

// ---- C: help, usage, progress -------------------------------------------------------------------

TEST(AfntoolDiagnostics, HelpIsOneScreenWithDetailPerMethod)
{
    const CliResult h = runAfntool({ "--help" });
    ASSERT_EQ(h.exitCode, 0) << h.err;
    EXPECT_LE(countOf(h.out, "\n"), 48) << h.out;
    EXPECT_EQ(countOf(h.out, "positionLimit"), 0) << "parameters are under --help METHOD";
    for (const char* method : { "identity", "ta", "svgf", "bmfr", "afn" })
        EXPECT_NE(h.out.find(std::string("\n  ") + method + " "), std::string::npos) << method;

    const CliResult s = runAfntool({ "--help", "svgf" });
    ASSERT_EQ(s.exitCode, 0) << s.err;
    EXPECT_EQ(s.out.rfind("svgf: ", 0), 0u) << s.out;
    EXPECT_EQ(countOf(s.out, "  positionLimit="), 1) << s.out;
    EXPECT_EQ(countOf(s.out, "  sigmaL="), 1) << s.out;
    EXPECT_EQ(countOf(s.out, "  normal.space=world"), 1) << s.out;

    expectCleanError(runAfntool({ "--help", "svfg" }), "did you mean 'svgf'?");
}

TEST(AfntoolDiagnostics, NoArgumentsPrintsUsage)
{
    // Like oiiotool: usage on stdout, exit code 0.
    const CliResult r = runAfntool({});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("Usage: afntool"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("afntool --help"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(AfntoolDiagnostics, ProgressLinesAndSummaryWhenNotATerminal)
{
    // The runner's stderr is a file, as in a farm log: a plain line per frame and a summary.
    TempDir dir;
    const CliResult r = runAfntool({ "--frames", "0-2", kSequence, "--denoise:method=identity",
        "-o", dir.file("out.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* line : { "afntool: [1/3] ", "afntool: [2/3] ", "afntool: [3/3] " })
        EXPECT_NE(r.err.find(line), std::string::npos) << line << "\n" << r.err;
    EXPECT_EQ(r.err.find("\033["), std::string::npos) << "no terminal control codes in a log";
    const size_t summary = r.err.find("afntool: 3 frames in ");
    ASSERT_NE(summary, std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" fps)\n", summary), std::string::npos) << r.err;
    EXPECT_GT(summary, r.err.find("afntool: [3/3] ")) << "the summary comes last";

    const CliResult q = runAfntool({ "-q", "--frames", "0-2", kSequence,
        "--denoise:method=identity", "-o", dir.file("q.####.exr") });
    ASSERT_EQ(q.exitCode, 0) << q.err;
    EXPECT_TRUE(q.err.empty()) << q.err;
}

TEST(AfntoolDiagnostics, DenoiseLogIsOneLinePerFrameAndVerboseGivesTheDetail)
{
    // A farm log: the run's facts (model, aux decision, speckle shares) once, then one line per
    // frame with its time, then the summary: at most 5 lines for 3 frames without warnings.
    TempDir dir;
    const CliResult r = runAfntool(
        { "--frames", "0-2", kSequence, "--denoise:method=afn", "-o", dir.file("out.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_LE(countOf(r.err, "\n"), 5) << r.err;
    EXPECT_EQ(countOf(r.err, "WARNING"), 0) << r.err;
    EXPECT_EQ(countOf(r.err, "afntool: --denoise: afn model "), 1) << r.err;
    EXPECT_EQ(countOf(r.err, "; aux "), 1) << r.err;
    for (const char* line : { "afntool: [1/3] ", "afntool: [2/3] ", "afntool: [3/3] " }) {
        const size_t at = r.err.find(line);
        ASSERT_NE(at, std::string::npos) << line << "\n" << r.err;
        std::string text = r.err.substr(at, r.err.find('\n', at) - at);
        text = text.substr(0, text.find(", history cut ")); // the share, where the trust cut
        EXPECT_EQ(text.substr(text.size() - 2), " s") << "the frame's time: " << text;
    }
    EXPECT_LT(r.err.find("afntool: --denoise: afn model "), r.err.find("afntool: [1/3] "));

    // -v: every frame's model and aux lines, as before the summary.
    const CliResult v = runAfntool({ "-v", "--frames", "0-2", kSequence, "--denoise:method=afn",
        "-o", dir.file("v.####.exr") });
    ASSERT_EQ(v.exitCode, 0) << v.err;
    EXPECT_EQ(countOf(v.err, "afntool: --denoise: afn model "), 3) << v.err;
    EXPECT_EQ(countOf(v.err, "afntool: --denoise: aux "), 3) << v.err;
    for (const char* frame : { "frame.0000.exr\n", "frame.0001.exr\n", "frame.0002.exr\n" })
        EXPECT_GE(countOf(v.err, frame), 2) << frame << "\n" << v.err;
}

TEST(AfntoolDiagnostics, DenoiseLogSaysWhatChangesMidRun)
{
    // The file's sample count goes from 1 to 16 spp at the second frame, and aux=auto's decision
    // with it: one line says what the run now does, when it happens, and only then.
    TempDir dir;
    const std::vector<std::string> channels = { "R", "G", "B", "albedo.R", "albedo.G", "albedo.B" };
    const std::string spp = "cycles.ViewLayer.samples";
    writeExr(dir.file("in.0000.exr"), channels, { { spp, "1" } });
    writeExr(dir.file("in.0001.exr"), channels, { { spp, "16" } });
    writeExr(dir.file("in.0002.exr"), channels, { { spp, "16" } });
    const CliResult r = runAfntool({ "--frames", "0-2", dir.file("in.####.exr"),
        "--denoise:method=ta", "-o", dir.file("out.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(countOf(r.err, "(aux=auto, 1 spp; speckle: albedo "), 1) << r.err;
    const size_t now = r.err.find("afntool: --denoise: ta now ");
    ASSERT_NE(now, std::string::npos) << r.err;
    EXPECT_NE(
        r.err.find("(aux=auto, 16 spp) " + dir.file("in.0001.exr") + "\n", now), std::string::npos)
        << r.err;
    EXPECT_GT(now, r.err.find("afntool: [1/3] ")) << "said when frame 1 is denoised";
    EXPECT_EQ(countOf(r.err, " now "), 1) << "frame 2 changes nothing:\n" << r.err;
}
