// SPDX-License-Identifier: Apache-2.0
// afntool --compare and --benchmark end to end on the bundled example sequence (2 frames, 320x180):
// identities, consistency of the printed means, report files, and the error paths.
#include "cli_runner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kSeq = std::string(AFN_EXAMPLES_DIR) + "/sequence/";
const std::string kFrames = kSeq + "frame.%04d.exr";
const std::string kRefs = kSeq + "reference.%04d.exr";

bool haveExample()
{
    return fs::exists(kSeq + "frame.0001.exr") && fs::exists(kSeq + "reference.0001.exr");
}

/// Every number following "key": in a JSON text, in order ("null" gives NaN).
std::vector<double> jsonNumbers(const std::string& json, const std::string& key)
{
    std::vector<double> out;
    const std::string needle = "\"" + key + "\": ";
    for (std::size_t p = json.find(needle); p != std::string::npos; p = json.find(needle, p + 1)) {
        const std::size_t v = p + needle.size();
        out.push_back(
            json.compare(v, 4, "null") == 0 ? NAN : std::strtod(json.c_str() + v, nullptr));
    }
    return out;
}

std::string readText(const std::string& path)
{
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

TEST(AfntoolCompare, SequenceAgainstItselfIsPerfect)
{
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    const CliResult r = runAfntool({ "--frames", "0-1", kFrames, "--compare", kFrames, "--json" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<double> ssim = jsonNumbers(r.out, "ssim"), rmse = jsonNumbers(r.out, "rmse");
    ASSERT_EQ(ssim.size(), 3u) << r.out; // two frames and the mean
    for (double v : ssim)
        EXPECT_NEAR(v, 1.0, 1e-12);
    for (double v : rmse)
        EXPECT_EQ(v, 0.0);
    for (double v : jsonNumbers(r.out, "psnr"))
        EXPECT_TRUE(std::isnan(v)) << "inf is written as null";
    const std::vector<double> tge = jsonNumbers(r.out, "tge");
    ASSERT_EQ(tge.size(), 2u); // frame 1 and the mean: frame 0 has no previous frame
    EXPECT_EQ(tge[0], 0.0);
}

TEST(AfntoolCompare, MeansAreMeansOfFrames)
{
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    const CliResult r = runAfntool({ "--frames", "0-1", kFrames, "--compare", kRefs, "--json" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* key : { "psnr", "ssim", "rmse", "smape", "rmseLinear" }) {
        const std::vector<double> v = jsonNumbers(r.out, key);
        ASSERT_EQ(v.size(), 3u) << key;
        EXPECT_NEAR(v[2], 0.5 * (v[0] + v[1]), 1e-6 * std::abs(v[2])) << key;
    }
    // A 1-spp input is far from its reference, and PSNR agrees with RMSE on every frame.
    const std::vector<double> psnr = jsonNumbers(r.out, "psnr"), rmse = jsonNumbers(r.out, "rmse");
    for (int i = 0; i < 2; ++i) {
        EXPECT_LT(psnr[i], 30.0);
        EXPECT_NEAR(psnr[i], -20.0 * std::log10(rmse[i]), 1e-5);
    }
    const CliResult text = runAfntool({ "--frames", "0-1", kFrames, "--compare", kRefs });
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("mean"), std::string::npos) << text.out;
}

TEST(AfntoolCompare, ErrorsNameTheFile)
{
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    CliResult r
        = runAfntool({ "--frames", "0-1", kFrames, "--compare", kSeq + "missing.%04d.exr" });
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("missing.0000.exr"), std::string::npos) << r.err;
    r = runAfntool({ std::string(AFN_TEST_DATA) + "/blender_64x36.exr", "--compare",
        kSeq + "reference.0000.exr" });
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("does not match"), std::string::npos) << r.err;
    r = runAfntool({ "--frames", "0-1", kFrames, "--benchmark:methods=ta" });
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--compare"), std::string::npos) << r.err;
}

TEST(AfntoolCompare, BenchmarkWritesTheReport)
{
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    TempDir dir;
    const std::string out = dir.file("report");
    const CliResult r = runAfntool({ "--frames", "0-1", kFrames, "--benchmark:methods=ta,nosuch",
        "--compare", kRefs, "--report", out, "-q" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : { "results.json", "results.csv", "runtime-vs-error.svg", "index.html",
             "crop_f1_ta.png", "crop_f1_reference.png", "crop_f1_noisy_input.png" })
        EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
    const std::string json = readText(out + "/results.json");
    EXPECT_NE(json.find("method 'nosuch' is not in this build"), std::string::npos);
    const std::string csv = readText(out + "/results.csv");
    std::size_t rows = 0;
    for (char c : csv)
        rows += c == '\n';
    EXPECT_EQ(rows, 1u + 2u * 3u) << csv; // header; noisy and ta: 2 frames + mean each
    const std::string svg = readText(out + "/runtime-vs-error.svg");
    EXPECT_NE(svg.find(">ta</text>"), std::string::npos);
    const std::string html = readText(out + "/index.html");
    EXPECT_NE(html.find("<img src=\"runtime-vs-error.svg\""), std::string::npos);
    for (const auto& e : dir.entries())
        EXPECT_EQ(e.find(".tmp"), std::string::npos) << e;
}

TEST(AfntoolCompare, SizeBenchmarkTimesGeneratedFrames)
{
    const CliResult r = runAfntool(
        { "--benchmark:size=64x36,128x72:methods=ta:frames=1:warmup=0", "--json", "-q" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<double> ms = jsonNumbers(r.out, "medianMs");
    ASSERT_EQ(ms.size(), 2u) << r.out;
    for (double v : ms)
        EXPECT_GT(v, 0.0);
    EXPECT_NE(
        runAfntool({ "--benchmark:size=64by36" }).err.find("WIDTHxHEIGHT"), std::string::npos);
}

// rounds=R repeats the sweep: each point's medians are over R x frames timed frames.
TEST(AfntoolCompare, SizeBenchmarkRoundsRepeatTheSweep)
{
    const CliResult r = runAfntool(
        { "--benchmark:size=64x36,32x18:methods=ta:frames=2:warmup=0:rounds=3", "--json", "-q" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(jsonNumbers(r.out, "rounds"), std::vector<double> { 3.0 }) << r.out;
    EXPECT_EQ(jsonNumbers(r.out, "frames"), (std::vector<double> { 6.0, 6.0 })) << r.out;
    const CliResult bad = runAfntool({ "--benchmark:size=64x36:methods=ta:rounds=two" });
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("afntool ERROR: --benchmark: frames, warmup and rounds expect integers"),
        std::string::npos)
        << bad.err;
}

// afn's engine report: GFLOP/s per stage beside the dnnl_sgemm yardstick, heap per megapixel.
TEST(AfntoolCompare, SizeBenchmarkReportsEngineAndHeap)
{
    const CliResult r
        = runAfntool({ "--benchmark:size=64x36:methods=afn,ta:frames=1:warmup=0", "--json", "-q" });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<double> heap = jsonNumbers(r.out, "heapMiBPerMegapixel");
    ASSERT_EQ(heap.size(), 2u) << r.out;
    for (double v : heap)
        EXPECT_GT(v, 0.0);
    if (r.out.find("\"engine\"") == std::string::npos)
        GTEST_SKIP() << "afn has no weights in this build: no engine report";
    const std::vector<double> gflop = jsonNumbers(r.out, "gflopPerFrame");
    // prediction, pred-convs (the prediction less its input preparation), filtering, refinement,
    // network (the three stages)
    ASSERT_EQ(gflop.size(), 5u) << r.out;
    EXPECT_EQ(gflop[1], gflop[0]);
    EXPECT_NEAR(gflop[4], gflop[0] + gflop[2] + gflop[3], 1e-9);
    const std::vector<double> ms = jsonNumbers(r.out, "msPerFrame");
    ASSERT_EQ(ms.size(), 5u) << r.out;
    EXPECT_GT(ms[1], 0.0);
    EXPECT_LT(ms[1], ms[0]); // the input preparation took some time
    EXPECT_NEAR(ms[4], ms[0] + ms[2] + ms[3], 1e-6); // as written in the JSON
    for (double v : jsonNumbers(r.out, "gflops"))
        EXPECT_GT(v, 0.0);
    // The stages below the GEMM rate say why (the prediction: its input preparation).
    EXPECT_NE(r.out.find("\"note\": \"includes its input preparation"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("exponentials per pixel"), std::string::npos) << r.out;
    // Each point says what its convolutions ran in; their share is of that precision's GEMM.
    const bool bf16 = r.out.find("\"precision\": \"bf16\"") != std::string::npos;
    EXPECT_TRUE(bf16 || r.out.find("\"precision\": \"fp32\"") != std::string::npos) << r.out;
    // The kernels: amx (bf16 convolutions on AMX tiles), avx512 or portable.
    const bool amx = r.out.find("\"kernels\": \"amx\"") != std::string::npos;
    EXPECT_TRUE(amx || r.out.find("\"kernels\": \"avx512\"") != std::string::npos
        || r.out.find("\"kernels\": \"portable\"") != std::string::npos)
        << r.out;
    EXPECT_TRUE(!amx || bf16) << r.out;
#ifdef AFN_HAS_DNNL
    for (double v : jsonNumbers(r.out, "peakGflops"))
        EXPECT_GT(v, 0.0);
    // The bf16 yardstick: measured, or why not (oneDNN without a bf16 matmul for this CPU).
    const bool bf16Gemm = r.out.find("\"bf16Gemm\": {\"available\": true") != std::string::npos;
    if (bf16Gemm)
        for (double v : jsonNumbers(r.out, "bf16PeakNGflops"))
            EXPECT_GT(v, 0.0);
    else
        EXPECT_NE(r.out.find("\"why\": \"oneDNN"), std::string::npos) << r.out;
    if (!bf16 || bf16Gemm)
        for (double v : jsonNumbers(r.out, "fractionOfGemmPeak"))
            EXPECT_GT(v, 0.0);
#endif
}

} // namespace
