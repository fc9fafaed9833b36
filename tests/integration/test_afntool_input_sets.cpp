// SPDX-License-Identifier: Apache-2.0
// Input-aware afn end to end through afntool: EXR sequences holding only some of the
// passes (colour; + albedo + normal; + depth; + motion) are denoised with the model trained for
// them (at every quality tier), the path is stated by --info and in every frame's log line, a
// model for fewer inputs than the file has is warned about, and weights lacking a model for the
// file's inputs are an error.
#include "cli_runner.h"
#include "image_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr int kW = 48, kH = 32, kFrames = 3;

struct Passes {
    bool albedo = false, normal = false, depth = false, motion = false;
};

/// A noisy checker moving 1 px right per frame, with only the passes asked for (generic names);
/// `samples`: the header's cycles.ViewLayer.samples, as Blender writes it (none when null).
void writeSequence(const TempDir& dir, const Passes& p, const char* samples = nullptr)
{
    std::vector<std::string> names = { "R", "G", "B" };
    if (p.albedo)
        names.insert(names.end(), { "albedo.R", "albedo.G", "albedo.B" });
    if (p.normal)
        names.insert(names.end(), { "N.X", "N.Y", "N.Z" });
    if (p.depth)
        names.push_back("Z");
    if (p.motion)
        names.insert(names.end(), { "motion.X", "motion.Y" });
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 2.0f);
    for (int f = 0; f < kFrames; ++f) {
        OIIO::ImageSpec spec(kW, kH, int(names.size()), OIIO::TypeDesc::FLOAT);
        spec.channelnames = names;
        if (samples)
            spec.attribute("cycles.ViewLayer.samples", samples);
        std::vector<float> px;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float a = (((x - f) / 8 + y / 8) % 2) ? 0.8f : 0.2f;
                for (int c = 0; c < 3; ++c)
                    px.push_back(a * u(rng)); // colour: albedo x noisy unit lighting
                if (p.albedo)
                    px.insert(px.end(), { a, a, a });
                if (p.normal)
                    px.insert(px.end(), { 0.0f, 0.0f, 1.0f });
                if (p.depth)
                    px.push_back(2.0f + 0.01f * float(y));
                if (p.motion)
                    px.insert(px.end(), { -1.0f, 0.0f }); // to previous: one pixel left
            }
        char name[32];
        std::snprintf(name, sizeof name, "in.%04d.exr", f + 1);
        ASSERT_TRUE(writeImage(dir.file(name), spec, px)) << name;
    }
}

/// Every weights file the build embeds must exist for these expectations.
bool shippedModels()
{
    for (const char* f : { "afn.afnw", "afn-color.afnw", "afn-albedo-normal.afnw" })
        if (!std::ifstream(std::string(AFN_SOURCE_DIR) + "/weights/" + f))
            return false;
    return true;
}

struct Case {
    const char* label;
    Passes passes;
    const char* model; ///< expected AFN_STAT_AFN_MODEL text (prefix)
    bool fallback; ///< a model for fewer inputs than the file has (warned)
};

const Case kCases[] = {
    { "color", {}, "model color, single-frame (no temporal branch: no motion or position)", false },
    { "albedo+normal", { true, true, false, false },
        "model color+albedo+normal, single-frame (no temporal branch: no motion or position)",
        false },
    // Without a history the temporal model runs single-frame (model_set.h).
    { "albedo+normal+depth", { true, true, true, false },
        "model color+albedo+normal+depth+temporal, single-frame (no motion or position: the "
        "temporal branch reads this frame)",
        false },
    { "albedo+depth", { true, false, true, false },
        "model color, single-frame (no temporal branch: no motion or position); not used: "
        "albedo,depth",
        true },
    { "all", { true, true, true, true }, "model color+albedo+normal+depth+temporal, temporal",
        false },
    { "color+motion", { false, false, false, true },
        "model color, single-frame (no temporal branch: the model has none); not used: temporal",
        true },
};

/// Mean absolute difference of two equally sized images.
double meanAbsDiff(const std::vector<float>& a, const std::vector<float>& b)
{
    double s = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
        s += std::fabs(a[k] - b[k]);
    return a.empty() ? 0.0 : s / double(a.size());
}

} // namespace

TEST(AfntoolInputSets, EachCombinationRunsItsModelAndSaysSo)
{
    if (!shippedModels())
        GTEST_SKIP() << "the per-input-set weights are not in weights/";
    for (const Case& c : kCases) {
        SCOPED_TRACE(c.label);
        TempDir dir;
        writeSequence(dir, c.passes);
        const CliResult info = runAfntool({ "--info", dir.file("in.0001.exr") });
        ASSERT_EQ(info.exitCode, 0) << info.err;
        EXPECT_NE(info.out.find(std::string("  afn: ") + c.model + "\n"), std::string::npos)
            << info.out;

        const CliResult r = runAfntool({ "-v", "--frames", "1-3", dir.file("in.####.exr"),
            "--denoise:method=afn", "-o", dir.file("out.####.exr") });
        ASSERT_EQ(r.exitCode, 0) << r.err;
        for (int f = 1; f <= kFrames; ++f) {
            const std::string line = std::string("afntool: --denoise: afn ") + c.model + " "
                + dir.file("in.000" + std::to_string(f) + ".exr");
            EXPECT_NE(r.err.find(line), std::string::npos) << "frame " << f << ":\n" << r.err;
        }
        const bool warned = r.err.find("afntool WARNING: --denoise: afn has no model for all")
            != std::string::npos;
        EXPECT_EQ(warned, c.fallback) << r.err;
        // The output is a denoised image: finite, and smoother than the noisy colour.
        const ReadBack in = readImage(dir.file("in.0003.exr"));
        const ReadBack out = readImage(dir.file("out.0003.exr"));
        ASSERT_EQ(out.pixels.size(), std::size_t(kW) * kH * 3);
        std::vector<float> inRgb;
        for (int k = 0; k < kW * kH; ++k)
            for (int ch = 0; ch < 3; ++ch)
                inRgb.push_back(in.pixels[std::size_t(k) * in.spec.nchannels + ch]);
        double rough = 0.0, roughIn = 0.0; // mean |horizontal neighbour difference|
        for (int y = 0; y < kH; ++y)
            for (int x = 1; x < kW; ++x)
                for (int ch = 0; ch < 3; ++ch) {
                    const std::size_t k = (std::size_t(y) * kW + x) * 3 + ch;
                    ASSERT_TRUE(std::isfinite(out.pixels[k]));
                    rough += std::fabs(out.pixels[k] - out.pixels[k - 3]);
                    roughIn += std::fabs(inRgb[k] - inRgb[k - 3]);
                }
        EXPECT_LT(rough, 0.7 * roughIn);
    }
}

TEST(AfntoolInputSets, UnboundRoleChoosesTheSmallerModel)
{
    if (!shippedModels())
        GTEST_SKIP() << "the per-input-set weights are not in weights/";
    TempDir dir;
    writeSequence(dir, { true, true, true, true });
    // --aov ROLE=none runs as if the file lacked the pass: the same model and pixels as a file
    // without it.
    const CliResult r
        = runAfntool({ "--frames", "1-3", "--aov", "depth=none", "--aov", "motion=none",
            dir.file("in.####.exr"), "--denoise:method=afn", "-o", dir.file("a.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("afn model color+albedo+normal, single-frame (no temporal branch: no "
                         "motion or position);"),
        std::string::npos)
        << r.err;
    TempDir plain;
    writeSequence(plain, { true, true, false, false });
    const CliResult p = runAfntool({ "--frames", "1-3", plain.file("in.####.exr"),
        "--denoise:method=afn", "-o", plain.file("b.####.exr") });
    ASSERT_EQ(p.exitCode, 0) << p.err;
    const ReadBack a = readImage(dir.file("a.0003.exr"));
    const ReadBack b = readImage(plain.file("b.0003.exr"));
    ASSERT_FALSE(a.pixels.empty());
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(meanAbsDiff(a.pixels, b.pixels), 0.0);
    // Colour cannot be unbound.
    const CliResult c = runAfntool({ "--aov", "color=none", "--info", dir.file("in.0001.exr") });
    EXPECT_NE(c.exitCode, 0);
    EXPECT_NE(c.err.find("afntool ERROR: "), std::string::npos) << c.err;
}

TEST(AfntoolInputSets, EveryQualityTierRunsTheChosenModel)
{
    if (!shippedModels())
        GTEST_SKIP() << "the per-input-set weights are not in weights/";
    // The model chosen per frame feeds the same tier runner: each tier runs on a colour-only and
    // a no-motion file with that file's model; balanced is the default, fast and high differ.
    for (const Case& c : { kCases[0], kCases[1] }) {
        SCOPED_TRACE(c.label);
        TempDir dir;
        writeSequence(dir, c.passes);
        std::vector<std::vector<float>> out;
        for (const char* q : { "", ":quality=balanced", ":quality=fast", ":quality=high" }) {
            SCOPED_TRACE(q);
            const std::string o = "out" + std::to_string(out.size()) + ".####.exr";
            const CliResult r = runAfntool({ "--frames", "1-3", dir.file("in.####.exr"),
                std::string("--denoise:method=afn") + q, "-o", dir.file(o) });
            ASSERT_EQ(r.exitCode, 0) << r.err;
            EXPECT_NE(
                r.err.find(std::string("afntool: --denoise: afn ") + c.model), std::string::npos)
                << r.err;
            out.push_back(readImage(dir.file(o.substr(0, o.find('#')) + "0003.exr")).pixels);
            ASSERT_EQ(out.back().size(), std::size_t(kW) * kH * 3);
            for (float v : out.back())
                ASSERT_TRUE(std::isfinite(v));
        }
        EXPECT_EQ(meanAbsDiff(out[0], out[1]), 0.0); // balanced is the default
        EXPECT_GT(meanAbsDiff(out[1], out[2]), 0.0); // fast: no refinement
        EXPECT_GT(meanAbsDiff(out[1], out[3]), 0.0); // high: four-flip ensemble
    }
}

// The model trained nearest the frame's sample count (1, 4 or 16 spp; in log2, a tie to the
// lower): the file's header decides, :spp=N overrides, and the log says which model ran. A 64-spp
// file gets the 16-spp model (AFN large is not built in: lib/core/methods/afn/CMakeLists.txt).
TEST(AfntoolInputSets, SampleCountChoosesTheModel)
{
    for (const char* f : { "afn-spp4.afnw", "afn-spp16.afnw" })
        if (!shippedModels() || !std::ifstream(std::string(AFN_SOURCE_DIR) + "/weights/" + f))
            GTEST_SKIP() << "the 4- and 16-spp weights are not in weights/";
    const std::string high = "model color+albedo+normal+depth+temporal (16 spp), temporal";
    const std::string mid = "model color+albedo+normal+depth+temporal (4 spp), temporal";
    const std::string low = "model color+albedo+normal+depth+temporal, temporal";
    const std::string top = high;
    TempDir dir;
    writeSequence(dir, { true, true, true, true }, "64");
    const CliResult info = runAfntool({ "--info", dir.file("in.0001.exr") });
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("samples per pixel: 64"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("  afn: " + top + "\n"), std::string::npos) << info.out;
    std::vector<std::vector<float>> out;
    for (const auto& [param, model] :
        { std::pair<std::string, std::string> { "", top }, { ":spp=1", low }, { ":spp=12", high },
            { ":spp=2", low }, { ":spp=16", high }, { ":spp=3", mid }, { ":spp=8", mid } }) {
        SCOPED_TRACE(param);
        const std::string o = "out" + std::to_string(out.size()) + ".####.exr";
        const CliResult r = runAfntool({ "-v", "--frames", "1-3", dir.file("in.####.exr"),
            "--denoise:method=afn" + param, "-o", dir.file(o) });
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.err.find("afntool: --denoise: afn " + model + " "), std::string::npos) << r.err;
        out.push_back(readImage(dir.file(o.substr(0, o.find('#')) + "0003.exr")).pixels);
        ASSERT_EQ(out.back().size(), std::size_t(kW) * kH * 3);
    }
    EXPECT_GT(meanAbsDiff(out[0], out[1]), 0.0); // two models, two results
    EXPECT_EQ(meanAbsDiff(out[2], out[4]), 0.0); // the same 16-spp model
    EXPECT_EQ(meanAbsDiff(out[1], out[3]), 0.0); // the same 1-spp model
    EXPECT_EQ(meanAbsDiff(out[0], out[2]), 0.0); // 64 spp: the 16-spp model
    EXPECT_EQ(meanAbsDiff(out[5], out[6]), 0.0); // the same 4-spp model
    EXPECT_GT(meanAbsDiff(out[5], out[1]), 0.0);
    EXPECT_GT(meanAbsDiff(out[5], out[2]), 0.0);
}

TEST(AfntoolInputSets, WeightsWithoutAModelForTheInputsAreAnError)
{
    // The full-input archive alone (an --weights override replaces the built-in models) has no
    // model for a colour-only file: an error, never that model on inputs it was not trained for.
    const std::string full = std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw";
    TempDir dir;
    writeSequence(dir, {});
    const CliResult r = runAfntool({ "--frames", "1-3", dir.file("in.####.exr"), "--weights", full,
        "--denoise:method=afn", "-o", dir.file("out.####.exr") });
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("afntool ERROR: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no weights for the inputs color (the models available are for: "
                         "color+albedo+normal+depth+temporal)"),
        std::string::npos)
        << r.err;
    EXPECT_EQ(dir.entries().size(), std::size_t(kFrames)) << "no output may be written";
    const CliResult info = runAfntool({ "--weights", full, "--info", dir.file("in.0001.exr") });
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("  afn: error: "), std::string::npos) << info.out;
    // The same weights serve a file with every input.
    TempDir all;
    writeSequence(all, { true, true, true, true });
    const CliResult ok = runAfntool({ "--frames", "1-3", all.file("in.####.exr"), "--weights", full,
        "--denoise:method=afn", "-o", all.file("out.####.exr") });
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
}

// aux=auto and the sample count (AFN_AUX_TRUSTED_SPP, stages/aux_prefilter.h): the example frame's
// albedo follows the gold torus' specular bounces and is found noisy at its own 1 spp; the same
// pixels declared 16 spp are used as given (the albedo's grain limited over time), in --info's
// prediction and in the run.
TEST(AfntoolInputSets, AuxAutoUsesTheBuffersAsGivenFromSixteenSpp)
{
    TempDir dir;
    const ReadBack frame = readImage(std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.0000.exr");
    ASSERT_FALSE(frame.pixels.empty());
    for (const char* samples : { "1", "16" }) {
        SCOPED_TRACE(samples);
        OIIO::ImageSpec spec = frame.spec;
        spec.set_format(OIIO::TypeFloat);
        spec.channelformats.clear();
        spec.attribute("cycles.ViewLayer.samples", samples);
        const std::string path = dir.file(std::string("s") + samples + ".exr");
        ASSERT_TRUE(writeImage(path, spec, frame.pixels));
        const bool trusted = std::string(samples) == "16";
        const CliResult info = runAfntool({ "--info", path });
        ASSERT_EQ(info.exitCode, 0) << info.err;
        EXPECT_NE(info.out.find(
                      trusted ? "aux=auto: clean, albedo grain limited\n" : "aux=auto: noisy\n"),
            std::string::npos)
            << info.out;
        const CliResult run
            = runAfntool({ path, "--denoise:method=svgf", "-o", dir.file("out.exr") });
        ASSERT_EQ(run.exitCode, 0) << run.err;
        EXPECT_NE(
            run.err.find(std::string(trusted ? "aux clean, albedo grain limited" : "aux noisy")
                + " (aux=auto, " + samples + " spp;"),
            std::string::npos)
            << run.err;
    }
}
