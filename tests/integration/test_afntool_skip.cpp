// SPDX-License-Identifier: Apache-2.0
// Work skipping through afntool (docs/work-skipping.md): with a sky (depth inf) and a user mask
// channel (:mask=CHANNEL), every method's output on the pixels that need denoising is
// bit-identical to skip=off on every frame, the per-frame log states the skipped share, and a
// mask channel the file lacks is an error naming it.
#include "cli_runner.h"
#include "image_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {

constexpr int kW = 96, kH = 64, kSky = 24; ///< rows 0..23 sky; matte covers columns 0..31
///< (bmfr's 32-pixel blocks right of column 35 hold no needed pixel)

/// Frame `f` of a noisy sequence: R,G,B, albedo, N, Z (inf in the sky), motion, matte.R.
void writeFrame(const std::string& path, int f)
{
    const std::vector<std::string> names = { "R", "G", "B", "albedo.R", "albedo.G", "albedo.B",
        "N.X", "N.Y", "N.Z", "Z", "motionvector.X", "motionvector.Y", "matte.R" };
    OIIO::ImageSpec spec(kW, kH, static_cast<int>(names.size()), OIIO::TypeFloat);
    spec.channelnames = names;
    std::vector<float> px(static_cast<std::size_t>(kW) * kH * names.size());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* p = &px[(static_cast<std::size_t>(y) * kW + x) * names.size()];
            std::uint32_t s = static_cast<std::uint32_t>((y * kW + x) * 3 + f * 7919);
            for (int c = 0; c < 3; ++c) {
                s = s * 1664525u + 1013904223u;
                const float u = static_cast<float>(s >> 8) / 16777216.0f;
                p[c] = y < kSky ? 0.5f + 0.1f * c : (0.2f + 0.1f * ((x / 5 + c) % 3)) * 2.0f * u;
                p[3 + c] = 0.4f + 0.1f * ((x / 7 + y / 5 + c) % 3);
            }
            p[6] = 0.0f, p[7] = 0.0f, p[8] = 1.0f;
            // The matte follows an object's silhouette: a depth edge at column 32 (svgf's temporal
            // exactness across a mask through continuous geometry: docs/work-skipping.md).
            p[9] = y < kSky ? std::numeric_limits<float>::infinity()
                            : (x < 32 ? 4.0f : 500.0f) + 0.05f * x;
            p[10] = p[11] = 0.0f;
            p[12] = x < 32 ? 1.0f : 0.0f;
        }
    ASSERT_TRUE(writeImage(path, spec, px)) << path;
}

} // namespace

TEST(AfntoolSkip, NeededPixelsBitIdenticalToSkipOffForEveryMethod)
{
    TempDir dir;
    for (int f = 0; f < 4; ++f)
        writeFrame(dir.file("in.000" + std::to_string(f) + ".exr"), f);
    const std::string in = dir.file("in.####.exr");
    for (const char* method : { "ta", "svgf", "bmfr" }) {
        // svgf's history trust sees the skipped pixels' (other) history in its blocks
        // (docs/work-skipping.md): bit-identity holds for it with antilag=0.
        const std::string m = std::string("--denoise:method=") + method + ":mask=matte.R"
            + (std::string(method) == "svgf" ? ":antilag=0" : "");
        const CliResult on
            = runAfntool({ "--frames", "0-3", in, m, "-o", dir.file("on.####.exr") });
        ASSERT_EQ(on.exitCode, 0) << on.err;
        // 24 sky rows + the right 64 columns of the other 40: (24 * 96 + 40 * 64) / (96 * 64).
        EXPECT_NE(on.err.find("skipped 79.17 % of the pixels"), std::string::npos) << on.err;
        const CliResult off = runAfntool(
            { "--frames", "0-3", in, m + ":skip=off", "-o", dir.file("off.####.exr") });
        ASSERT_EQ(off.exitCode, 0) << off.err;
        EXPECT_EQ(off.err.find("skipped"), std::string::npos) << off.err;
        bool skippedDiffer = false;
        for (int f = 0; f < 4; ++f) {
            const std::string n = ".000" + std::to_string(f) + ".exr";
            const ReadBack a = readImage(dir.file("on" + n)), b = readImage(dir.file("off" + n));
            ASSERT_FALSE(a.pixels.empty());
            ASSERT_EQ(a.pixels.size(), b.pixels.size());
            const int ch = a.spec.nchannels;
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const std::size_t i = (static_cast<std::size_t>(y) * kW + x) * ch + c;
                        if (y >= kSky && x < 32)
                            ASSERT_EQ(a.pixels[i], b.pixels[i])
                                << method << " frame " << f << " at " << x << "," << y;
                        else
                            skippedDiffer = skippedDiffer || a.pixels[i] != b.pixels[i];
                    }
        }
        if (std::string(method) != "ta") // ta's whole output is its cheap path
            EXPECT_TRUE(skippedDiffer) << method << ": nothing was skipped";
    }
}

TEST(AfntoolSkip, MissingMaskChannelIsAnErrorNamingIt)
{
    TempDir dir;
    writeFrame(dir.file("in.exr"), 0);
    const CliResult r = runAfntool(
        { dir.file("in.exr"), "--denoise:method=svgf:mask=matte.A", "-o", dir.file("o.exr") });
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("afntool ERROR: --denoise: mask channel 'matte.A' is not in the file"),
        std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("matte.R"), std::string::npos) << r.err; // suggested / listed
    const CliResult empty = runAfntool(
        { dir.file("in.exr"), "--denoise:method=svgf:mask=", "-o", dir.file("o.exr") });
    EXPECT_EQ(empty.exitCode, 1) << empty.err;
}

TEST(AfntoolSkip, SkyBenchmarkReportsBitIdenticalCoveredPixels)
{
    TempDir dir;
    const CliResult r = runAfntool({ "-q",
        "--benchmark:size=64x48:sky=0.6:methods=svgf,bmfr,afn:"
        "frames=2:warmup=1",
        "--report", dir.path() });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::FILE* f = std::fopen(dir.file("skip.csv").c_str(), "r");
    ASSERT_NE(f, nullptr);
    char line[512];
    auto split = [](const std::string& s) {
        std::vector<std::string> cells;
        std::size_t a = 0;
        for (std::size_t b; (b = s.find_first_of(",\n", a)) != std::string::npos; a = b + 1)
            cells.push_back(s.substr(a, b - a));
        if (a < s.size())
            cells.push_back(s.substr(a));
        return cells;
    };
    ASSERT_NE(std::fgets(line, sizeof line, f), nullptr);
    const std::vector<std::string> header = split(line);
    auto column = [&](const char* name) {
        return static_cast<std::size_t>(
            std::find(header.begin(), header.end(), name) - header.begin());
    };
    const std::size_t diff = column("coveredMaxDiff"), sky = column("coveredPsnrSky"),
                      off = column("coveredPsnrSkyOff");
    ASSERT_LT(off, header.size());
    std::vector<std::string> methods;
    while (std::fgets(line, sizeof line, f)) {
        const std::vector<std::string> c = split(line);
        ASSERT_EQ(c.size(), header.size()) << line;
        methods.push_back(c[0]);
        // Skipping changed no covered pixel: the largest difference is 0, the PSNRs are equal.
        EXPECT_EQ(std::stod(c[diff]), 0.0) << line;
        EXPECT_EQ(c[sky], c[off]) << line;
    }
    std::fclose(f);
    EXPECT_EQ(methods, (std::vector<std::string> { "svgf", "bmfr", "afn" }));
}
