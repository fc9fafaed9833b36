// SPDX-License-Identifier: Apache-2.0
// afntool --preroll end to end (farm chunks, docs/farm.md): for every temporal method, the
// bundled 8-frame sequence split into chunks 0-3 and 4-7 with --preroll 4 gives bit-identical
// float outputs to one sequential run; a shorter preroll is measured (printed, not asserted
// against a number) and must be closer to the sequential run than a cold start. Error paths too.
#include "cli_runner.h"

#include "afn/afn.hpp"
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <tuple>

namespace fs = std::filesystem;

namespace {

const std::string kDir = std::string(AFN_EXAMPLES_DIR) + "/sequence";
const std::string kFrames = kDir + "/frame.####.exr";

bool haveExample()
{
    return fs::exists(kDir + "/frame.0000.exr") && fs::exists(kDir + "/frame.0007.exr");
}

void expectCleanError(const CliResult& r, const std::string& needle)
{
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(r.err.rfind("afntool ERROR: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
    EXPECT_LT(r.exitCode, 128) << "killed by a signal";
}

/// Denoise `frames` of the example with `method` and `preroll`, float outputs to out.####.exr.
void denoise(const std::string& method, const std::string& frames, int preroll,
    const std::string& outPattern)
{
    const CliResult r = runAfntool({ "-q", "--frames", frames, kFrames, "--preroll",
        std::to_string(preroll), "--denoise:method=" + method, "-d", "float", "-o", outPattern });
    ASSERT_EQ(r.exitCode, 0) << r.err;
}

std::vector<float> beauty(const std::string& path)
{
    afn::io::FrameImages img = afn::io::readFrame(path);
    return img.roles.at(afn::io::Role::Color).pixels;
}

/// Difference of a chunked run's frames to the sequential ones.
struct Difference {
    double maxAbs = 0.0; ///< largest |a - b| over every value
    double meanAbs = 0.0; ///< mean |a - b|
    double minPsnr = INFINITY; ///< worst frame's PSNR (afn's metric: on T(x), docs/metrics.md)
};

Difference difference(
    const std::string& chunked, const std::string& sequential, int first, int last)
{
    afn::DeviceRef device = afn::newDevice(afn::DeviceType::CPU);
    device.commit();
    Difference d;
    std::size_t count = 0;
    for (int f = first; f <= last; ++f) {
        const std::vector<float> a = beauty(afn::io::expandFramePattern(chunked, f));
        const std::vector<float> b = beauty(afn::io::expandFramePattern(sequential, f));
        EXPECT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
            const double e = std::fabs(static_cast<double>(a[i]) - b[i]);
            d.maxAbs = std::max(d.maxAbs, e);
            d.meanAbs += e;
        }
        count += a.size();
        const afn::io::FrameImages img
            = afn::io::readFrame(afn::io::expandFramePattern(chunked, f));
        const afn::io::RoleImage& c = img.roles.at(afn::io::Role::Color);
        AFNMetrics m {};
        EXPECT_TRUE(
            afn::computeMetrics(device, a.data(), b.data(), c.width, c.height, c.components, m));
        d.minPsnr = std::min(d.minPsnr, m.psnr);
    }
    d.meanAbs /= static_cast<double>(std::max<std::size_t>(count, 1));
    return d;
}

/// True when every written frame first..last has exactly the same pixel data in both runs.
void expectBitIdentical(
    const std::string& chunked, const std::string& sequential, int first, int last)
{
    for (int f = first; f <= last; ++f) {
        const std::vector<float> a = beauty(afn::io::expandFramePattern(chunked, f));
        const std::vector<float> b = beauty(afn::io::expandFramePattern(sequential, f));
        ASSERT_EQ(a.size(), b.size()) << "frame " << f;
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0)
            << "frame " << f << " differs from the sequential run";
    }
}

class TemporalMethod : public ::testing::TestWithParam<std::string> { };

TEST_P(TemporalMethod, ChunksWithPrerollMatchSequential)
{
    const std::string method = GetParam();
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    if (!afn::isFilterTypeReady(method.c_str()))
        GTEST_SKIP() << method << " has no weights in this build (afntool --methods)";
    TempDir dir;
    const std::string seq = dir.file("seq.####.exr"), chunked = dir.file("chunk.####.exr");
    denoise(method, "0-7", 0, seq);
    denoise(method, "0-3", 4, chunked); // clamped: nothing before frame 0
    denoise(method, "4-7", 4, chunked); // frames 0-3 rerun, unwritten
    expectBitIdentical(chunked, seq, 0, 7);
    for (int f : { 0, 1, 2, 3 }) // the second chunk wrote only its own frames
        EXPECT_TRUE(fs::exists(afn::io::expandFramePattern(chunked, f)));
    EXPECT_EQ(dir.entries().size(), 16u);

    // History partly covered: frames 2-3 (preroll 2) and none (cold start) before chunk 4-7.
    const std::string part = dir.file("p2.####.exr"), cold = dir.file("p0.####.exr");
    denoise(method, "4-7", 2, part);
    denoise(method, "4-7", 0, cold);
    EXPECT_FALSE(fs::exists(afn::io::expandFramePattern(part, 3))) << "a preroll frame was written";
    const Difference p2 = difference(part, seq, 4, 7), p0 = difference(cold, seq, 4, 7);
    std::printf("[ preroll  ] %s chunk 4-7 vs sequential: preroll 2: max %.6g mean %.6g "
                "min PSNR %.2f dB; preroll 0: max %.6g mean %.6g min PSNR %.2f dB\n",
        method.c_str(), p2.maxAbs, p2.meanAbs, p2.minPsnr, p0.maxAbs, p0.meanAbs, p0.minPsnr);
    RecordProperty("preroll2_mean_abs", std::to_string(p2.meanAbs));
    RecordProperty("preroll0_mean_abs", std::to_string(p0.meanAbs));
    EXPECT_GT(p0.meanAbs, 0.0) << "a cold start should differ: the method keeps no history?";
    EXPECT_LT(p2.meanAbs, p0.meanAbs) << "two frames of history should bring the chunk closer";
}

INSTANTIATE_TEST_SUITE_P(AfntoolPreroll, TemporalMethod,
    ::testing::Values("ta", "svgf", "bmfr", "afn"),
    [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(AfntoolPreroll, FeaturesFollowThePreroll)
{
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    TempDir dir;
    const std::string seq = dir.file("seq.####.exr"), chunked = dir.file("chunk.####.exr");
    for (const auto& [frames, preroll, out] :
        { std::tuple { "0-3", "0", seq }, std::tuple { "2-3", "2", chunked } }) {
        const CliResult r = runAfntool(
            { "-q", "--frames", frames, kFrames, "--preroll", preroll, "--features", out });
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_FALSE(fs::exists(afn::io::expandFramePattern(chunked, 1)));
    afn::io::ReadOptions all;
    all.keepAll = true;
    all.required = {};
    for (int f : { 2, 3 }) {
        const auto a = afn::io::readFrame(afn::io::expandFramePattern(chunked, f), all).all;
        const auto b = afn::io::readFrame(afn::io::expandFramePattern(seq, f), all).all;
        ASSERT_TRUE(a && b);
        ASSERT_EQ(a->channels, b->channels);
        ASSERT_FALSE(a->pixels.empty());
        EXPECT_EQ(a->pixels, b->pixels) << "features of frame " << f << " differ";
    }
}

TEST(AfntoolPreroll, BadCountsAreRefused)
{
    expectCleanError(runAfntool({ "--preroll", "-1" }), "--preroll must be >= 0");
    expectCleanError(runAfntool({ "--preroll", "four" }), "--preroll expects an integer");
    expectCleanError(runAfntool({ "--preroll", "2.5" }), "--preroll expects an integer");
    expectCleanError(runAfntool({ "--preroll" }), "--preroll needs an argument");
}

TEST(AfntoolPreroll, RefusedWhereMeaningless)
{
    TempDir dir;
    const std::string out = dir.file("o.####.exr");
    expectCleanError(runAfntool({ "--frames", "4-5", kFrames, "--preroll", "2", "-o", out }),
        "--preroll needs --denoise or --features");
    expectCleanError(runAfntool({ "--frames", "4-5", kFrames, "--preroll", "2",
                         "--benchmark:methods=ta", "--compare", kDir + "/reference.####.exr" }),
        "--preroll does not apply to --benchmark");
    expectCleanError(runAfntool({ kDir + "/frame.0004.exr", "--preroll", "2", "--denoise:method=ta",
                         "-o", dir.file("one.exr") }),
        "--preroll needs a frame pattern input");
    EXPECT_TRUE(dir.entries().empty());
}

TEST(AfntoolPreroll, HoleInTheSequenceIsNamed)
{
    if (!haveExample())
        GTEST_SKIP() << "examples/sequence not rendered";
    TempDir dir;
    for (int f : { 0, 1, 3, 4 }) // frame 2 missing: a hole, not the sequence start
        fs::create_symlink(afn::io::expandFramePattern(kFrames, f),
            afn::io::expandFramePattern(dir.file("in.####.exr"), f));
    const CliResult r = runAfntool({ "--frames", "4", dir.file("in.####.exr"), "--preroll", "3",
        "--denoise:method=ta", "-o", dir.file("out.####.exr") });
    expectCleanError(r, "frame 2 is missing but frame 1 exists");
    EXPECT_FALSE(fs::exists(dir.file("out.0004.exr")));

    // Walking back to the sequence start is a clamp, said on stderr.
    const CliResult c = runAfntool({ "--frames", "4", dir.file("in.####.exr"), "--preroll", "1",
        "--denoise:method=ta", "-o", dir.file("out.####.exr") });
    EXPECT_EQ(c.exitCode, 0) << c.err;
    const CliResult s = runAfntool({ "--frames", "1", dir.file("in.####.exr"), "--preroll", "3",
        "--denoise:method=ta", "-o", dir.file("out.####.exr") });
    EXPECT_EQ(s.exitCode, 0) << s.err;
    EXPECT_NE(s.err.find("--preroll: 1 of 3 frames before frame 1"), std::string::npos) << s.err;
}

} // namespace
