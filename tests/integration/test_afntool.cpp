// SPDX-License-Identifier: Apache-2.0
// afntool end to end: info/JSON on a real Blender EXR, conversion, AOV copying, sequences,
// previews, and every error path (clear message, non-zero exit, nothing half-written).
#include "cli_runner.h"

#include "afn/afn.hpp"
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace {

const std::string kBlender = std::string(AFN_TEST_DATA) + "/blender_64x36.exr";
const std::string kSequence = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.####.exr";
const std::string kFrame0 = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.0000.exr";

void expectCleanError(const CliResult& r, const std::string& needle)
{
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(r.err.rfind("afntool ERROR: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
    EXPECT_LT(r.exitCode, 128) << "killed by a signal";
}

/// Write a small EXR with the given channels, each channel c filled with value c + 0.25.
void writeExr(const std::string& path, int w, int h, const std::vector<std::string>& channels)
{
    std::vector<float> px(static_cast<size_t>(w) * h * channels.size());
    for (size_t i = 0; i < px.size(); ++i)
        px[i] = float(i % channels.size()) + 0.25f;
    afn::io::WriteOptions wo;
    wo.dataType = "float";
    afn::io::writeImageAtomic(path, w, h, channels, px.data(), wo);
}

TEST(Afntool, HelpListsMethodsAndParameters)
{
    const CliResult r = runAfntool({ "--help" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("identity"), std::string::npos);
    EXPECT_NE(r.out.find("normal.space=world"), std::string::npos);
    EXPECT_NE(r.out.find("--denoise:method=NAME"), std::string::npos);
    EXPECT_NE(r.out.find("--device cpu|cuda|auto"), std::string::npos);
    EXPECT_NE(r.out.find("only afn runs there"), std::string::npos);
}

TEST(Afntool, MethodsListsEveryMethodWithItsReadiness)
{
    const CliResult r = runAfntool({ "--methods" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string& m : afn::filterTypes()) {
        const std::string line
            = "\n" + m + (afn::isFilterTypeReady(m.c_str()) ? " ready " : " needs-weights ");
        EXPECT_NE(("\n" + r.out).find(line), std::string::npos) << m << "\n" << r.out;
    }
}

TEST(Afntool, InfoJsonMapsBlenderRoles)
{
    const CliResult r = runAfntool({ "--info", "--json", kBlender });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* key : { "\"file\"", "\"width\": 64", "\"height\": 36", "\"channels\"",
             "\"renderer\": \"blender\"" })
        EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
    const size_t roles = r.out.find("\"roles\": {");
    ASSERT_NE(roles, std::string::npos);
    const std::string rolesObj = r.out.substr(roles, r.out.find('}', roles) - roles);
    for (const char* role : { "color", "albedo", "normal", "depth", "position", "motion" })
        EXPECT_NE(rolesObj.find(std::string("\"") + role + "\": [\"ViewLayer."), std::string::npos)
            << role << " in " << rolesObj;
    EXPECT_NE(r.out.find("\"motion.yUp\": true"), std::string::npos);
    EXPECT_NE(r.out.find("\"samples\": 4,"), std::string::npos) << r.out; // cycles.*.samples
}

TEST(Afntool, InfoTextShowsStatisticsAndMissingRoles)
{
    TempDir dir;
    writeExr(dir.file("plain.exr"), 4, 3, { "R", "G", "B" });
    const CliResult r = runAfntool({ "--info", dir.file("plain.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("min 0.25  max 2.25  mean 1.25"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("albedo    (not found; looked for"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("samples per pixel: unknown"), std::string::npos) << r.out;
}

TEST(Afntool, InfoReportsAuxNoisePerRoleAndTheAutoChoice)
{
    // examples/sequence maps Blender's Denoising Albedo, which follows the gold torus' specular
    // bounces: noisy; the world-space Normal pass is first-hit: clean.
    const CliResult text = runAfntool({ "--info", kFrame0 });
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("noise: speckle"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("aux=auto: noisy"), std::string::npos) << text.out;
    const CliResult json = runAfntool({ "--info", "--json", kFrame0 });
    ASSERT_EQ(json.exitCode, 0) << json.err;
    for (const char* key :
        { "\"auxNoise\": {", "\"albedo\": {\"speckle\": ", "\"auxAuto\": \"noisy\"" })
        EXPECT_NE(json.out.find(key), std::string::npos) << key << "\n" << json.out;
}

TEST(Afntool, DenoiseLogsTheAuxModePerFrame)
{
    TempDir dir;
    // -v: the aux decision and speckle shares of every frame.
    const CliResult r = runAfntool({ "-v", "--frames", "0-1", kSequence,
        "--denoise:method=ta:aux=clean", "-o", dir.file("out.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(
        r.err.find("--denoise: aux clean (aux=clean, 1 spp; speckle: albedo "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("spp; speckle: albedo ", r.err.find("frame.0000.exr")), std::string::npos)
        << "a line for the second frame too:\n"
        << r.err;
    const CliResult a = runAfntool(
        { "--frames", "0-1", kSequence, "--denoise:method=ta", "-o", dir.file("auto.####.exr") });
    ASSERT_EQ(a.exitCode, 0) << a.err;
    EXPECT_NE(a.err.find("aux noisy (aux=auto, 1 spp;"), std::string::npos) << a.err;
    // From 16 spp (AFN_AUX_TRUSTED_SPP) aux=auto uses the buffers as given: the same speckle.
    const CliResult t = runAfntool({ "--frames", "0-1", kSequence, "--denoise:method=ta:spp=16",
        "-o", dir.file("trusted.####.exr") });
    ASSERT_EQ(t.exitCode, 0) << t.err;
    EXPECT_NE(t.err.find("aux clean, albedo grain limited (aux=auto, 16 spp;"), std::string::npos)
        << t.err;
}

TEST(Afntool, ConvertWritesTopLevelBeautyAndKeepsAovsOnRequest)
{
    TempDir dir;
    const std::string out = dir.file("out.exr"), outAovs = dir.file("aovs.exr");
    CliResult r = runAfntool({ kBlender, "-d", "float", "-o", out });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const afn::io::FileInfo info = afn::io::inspect(out);
    ASSERT_EQ(info.subimages.size(), 1u);
    EXPECT_EQ(info.subimages[0].channels, (std::vector<std::string> { "R", "G", "B", "A" }));
    // Pixel values equal the input beauty (float output, working space = the file's space).
    const afn::io::FrameImages in = afn::io::readFrame(kBlender);
    const afn::io::FrameImages back = afn::io::readFrame(out);
    const auto& a = in.roles.at(afn::io::Role::Color).pixels;
    const auto& b = back.roles.at(afn::io::Role::Color).pixels;
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i)
        ASSERT_NEAR(a[i], b[i], 1e-5f * std::max(1.0f, std::fabs(a[i]))) << i;

    r = runAfntool({ kBlender, "--keep-aovs", "-o", outAovs });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const afn::io::FileInfo kept = afn::io::inspect(outAovs);
    const auto& ch = kept.subimages[0].channels;
    EXPECT_NE(std::find(ch.begin(), ch.end(), "ViewLayer.Vector.X"), ch.end());
    EXPECT_NE(std::find(ch.begin(), ch.end(), "ViewLayer.Denoising Albedo.R"), ch.end());
    EXPECT_EQ(std::find(ch.begin(), ch.end(), "ViewLayer.Combined.R"), ch.end())
        << "beauty is top-level";
}

TEST(Afntool, MissingFileIsAClearError)
{
    TempDir dir;
    expectCleanError(runAfntool({ dir.file("nope.exr"), "-o", dir.file("o.exr") }), "nope.exr");
    EXPECT_EQ(dir.entries().size(), 0u);
}

TEST(Afntool, TruncatedExrIsAClearError)
{
    TempDir dir;
    const std::string good = dir.file("good.exr"), bad = dir.file("bad.exr");
    writeExr(good, 64, 64, { "R", "G", "B" });
    const auto size = fs::file_size(good);
    fs::copy_file(good, bad);
    fs::resize_file(bad, size / 2);
    expectCleanError(runAfntool({ bad, "-o", dir.file("o.exr") }), "bad.exr");
    EXPECT_FALSE(fs::exists(dir.file("o.exr")));
    EXPECT_EQ(dir.entries().size(), 2u) << "no temporary file left behind";
}

TEST(Afntool, FileWithoutColourNamesWhatWasLookedFor)
{
    TempDir dir;
    writeExr(dir.file("nocolor.exr"), 4, 4, { "N.X", "N.Y", "N.Z" });
    const CliResult r = runAfntool({ dir.file("nocolor.exr"), "-o", dir.file("o.exr") });
    expectCleanError(r, "nocolor.exr");
    EXPECT_NE(r.err.find("color"), std::string::npos);
    EXPECT_NE(r.err.find("R"), std::string::npos) << "names the channels looked for";
    EXPECT_FALSE(fs::exists(dir.file("o.exr")));
}

TEST(Afntool, UnwritableOutputIsAClearError)
{
    TempDir dir;
    writeExr(dir.file("in.exr"), 4, 4, { "R", "G", "B" });
    // The parent of the output is a regular file (fails even for root).
    expectCleanError(
        runAfntool({ dir.file("in.exr"), "-o", dir.file("in.exr") + "/o.exr" }), "o.exr");
    // The output names an existing directory.
    fs::create_directory(dir.file("adir"));
    expectCleanError(runAfntool({ dir.file("in.exr"), "-o", dir.file("adir") }), "adir");
    EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(Afntool, RefusesToOverwriteItsInput)
{
    TempDir dir;
    writeExr(dir.file("in.exr"), 4, 4, { "R", "G", "B" });
    const auto before = fs::file_size(dir.file("in.exr"));
    expectCleanError(
        runAfntool({ dir.file("in.exr"), "-d", "half", "-o", dir.file("in.exr") }), "in.exr");
    EXPECT_EQ(fs::file_size(dir.file("in.exr")), before);
}

TEST(Afntool, UnknownArgumentsAndMethods)
{
    expectCleanError(runAfntool({ "--frobnicate" }), "--frobnicate");
    expectCleanError(runAfntool({ kBlender, "--denoise:method=nope", "-o", "/tmp/x.exr" }), "nope");
    expectCleanError(runAfntool({ kBlender, "--denoise", "-o", "/tmp/x.exr" }), "method");
    expectCleanError(
        runAfntool({ kBlender, "-d", "int8", "-o", "/tmp/x.exr" }), "uint8, uint16, half or float");
}

TEST(Afntool, DeviceChoice)
{
    expectCleanError(runAfntool({ kFrame0, "--device", "gpu" }), "cpu, cuda or auto");
    const bool hasCuda = static_cast<bool>(afn::newDevice(afn::DeviceType::CUDA));
    TempDir dir;
    auto denoise = [&](const std::string& device, const std::string& prefix) {
        return runAfntool({ "--device", device, "--frames", "0-1", kSequence, "--denoise:method=ta",
            "-o", dir.file(prefix + ".####.exr") });
    };
    const CliResult cpu = denoise("cpu", "cpu");
    ASSERT_EQ(cpu.exitCode, 0) << cpu.err;
    EXPECT_EQ(cpu.err.find("note:"), std::string::npos) << cpu.err;
    // auto: ta runs on the CPU only, so the CPU is used, with a note saying why.
    const CliResult automatic = denoise("auto", "auto");
    ASSERT_EQ(automatic.exitCode, 0) << automatic.err;
    EXPECT_NE(automatic.err.find(hasCuda ? "runs on the CPU only" : "note: no CUDA device"),
        std::string::npos)
        << automatic.err;
    for (const char* f : { "0000", "0001" }) {
        const auto a = afn::io::readFrame(dir.file(std::string("cpu.") + f + ".exr"));
        const auto b = afn::io::readFrame(dir.file(std::string("auto.") + f + ".exr"));
        EXPECT_EQ(a.roles.at(afn::io::Role::Color).pixels, b.roles.at(afn::io::Role::Color).pixels)
            << f;
    }
    // cuda: an error without a CUDA device; with one, ta does not run there.
    expectCleanError(
        denoise("cuda", "cuda"), hasCuda ? "does not run on the cuda device" : "--device cuda: ");
}

TEST(Afntool, SequenceDenoiseWritesEveryFrame)
{
    TempDir dir;
    const CliResult r = runAfntool({ "--frames", "0-7", kSequence, "--denoise:method=identity",
        "-o", dir.file("out.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (int f = 0; f < 8; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "out.%04d.exr", f);
        EXPECT_TRUE(fs::exists(dir.file(name))) << name;
    }
    EXPECT_EQ(dir.entries().size(), 8u);
}

TEST(Afntool, FeaturesWriteTheNetworkInputsPerFrame)
{
    TempDir dir;
    const CliResult r
        = runAfntool({ "--frames", "0-1", kSequence, "--features", dir.file("features.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const afn::io::FileInfo info = afn::io::inspect(dir.file("features.0001.exr"));
    ASSERT_EQ(info.subimages.size(), 1u);
    std::vector<std::string> channels = info.subimages[0].channels;
    std::sort(channels.begin(), channels.end());
    const std::vector<std::string> want = { "accumulated.B", "accumulated.G", "accumulated.R",
        "albedo.B", "albedo.G", "albedo.R", "depth01.Z", "history01.Z", "historyTrust.Z",
        "irradiance.B", "irradiance.G", "irradiance.R", "normal01.B", "normal01.G", "normal01.R" };
    EXPECT_EQ(channels, want);
    for (const std::string& t : info.subimages[0].types)
        EXPECT_EQ(t, "float");
    expectCleanError(runAfntool({ kFrame0, "--features:method=identity", dir.file("f.exr") }),
        "has no feature outputs");
    // Every method with a history shows its trust map, svgf included.
    const CliResult s = runAfntool(
        { "--frames", "0-1", kSequence, "--features:method=svgf", dir.file("svgf.####.exr") });
    ASSERT_EQ(s.exitCode, 0) << s.err;
    EXPECT_EQ(afn::io::inspect(dir.file("svgf.0001.exr")).subimages[0].channels,
        std::vector<std::string> { "historyTrust.Z" });
}

TEST(Afntool, MissingFrameIsNamed)
{
    TempDir dir;
    expectCleanError(runAfntool({ "--frames", "0-9", kSequence, "-o", dir.file("out.####.exr") }),
        "frame.0008.exr");
    EXPECT_EQ(dir.entries().size(), 0u) << "nothing is written when a frame is missing";
}

TEST(Afntool, SequenceOutputNeedsAPattern)
{
    TempDir dir;
    expectCleanError(
        runAfntool({ "--frames", "0-1", kSequence, "-o", dir.file("out.exr") }), "pattern");
}

TEST(Afntool, PreviewAndContactSheet)
{
    TempDir dir;
    const CliResult r = runAfntool(
        { kFrame0, "--preview", dir.file("p.png"), "--contact-sheet", dir.file("c.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const afn::io::FileInfo p = afn::io::inspect(dir.file("p.png"));
    EXPECT_EQ(p.subimages[0].dataWindow.width, 320);
    EXPECT_EQ(p.subimages[0].dataWindow.height, 180);
    const afn::io::FileInfo c = afn::io::inspect(dir.file("c.png"));
    EXPECT_GT(c.subimages[0].dataWindow.width, 320);
    expectCleanError(
        runAfntool({ kFrame0, "--preview:view=NoSuchView", dir.file("q.png") }), "NoSuchView");
    EXPECT_FALSE(fs::exists(dir.file("q.png")));
}

} // namespace

TEST(Afntool, WeightsFileOverridesAndItsErrors)
{
    TempDir dir;
    const std::string weights = std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw";
    const CliResult global = runAfntool({ "--frames", "0-1", kSequence, "--weights", weights,
        "--denoise:method=afn", "-o", dir.file("g.####.exr") });
    ASSERT_EQ(global.exitCode, 0) << global.err;
    const CliResult mod = runAfntool({ "--frames", "0-1", kSequence,
        "--denoise:method=afn:weights=" + weights, "-o", dir.file("m.####.exr") });
    ASSERT_EQ(mod.exitCode, 0) << mod.err;
    for (const char* f : { "0000", "0001" }) {
        const auto a = afn::io::readFrame(dir.file(std::string("g.") + f + ".exr"));
        const auto b = afn::io::readFrame(dir.file(std::string("m.") + f + ".exr"));
        EXPECT_EQ(a.roles.at(afn::io::Role::Color).pixels, b.roles.at(afn::io::Role::Color).pixels)
            << f;
    }
    expectCleanError(runAfntool({ kFrame0, "--weights", dir.file("none.afnw"),
                         "--denoise:method=afn", "-o", dir.file("x.exr") }),
        "none.afnw");
    {
        std::ofstream junk(dir.file("junk.afnw"), std::ios::binary);
        junk << "definitely not a weights archive";
    }
    expectCleanError(runAfntool({ kFrame0, "--denoise:method=afn:weights=" + dir.file("junk.afnw"),
                         "-o", dir.file("x.exr") }),
        "invalid or corrupted weights");
    expectCleanError(runAfntool({ kFrame0, "--weights", weights, "--denoise:method=svgf", "-o",
                         dir.file("x.exr") }),
        "weights");
    EXPECT_FALSE(fs::exists(dir.file("x.exr"))) << "nothing is written on error";
}
