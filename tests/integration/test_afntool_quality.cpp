// SPDX-License-Identifier: Apache-2.0
// afntool --denoise:quality=fast|balanced|high end to end (filter/quality.h): balanced written
// out is bit-identical to no quality at all, afn's fast and high are different results, a method
// with one level gives the same pixels for all three, a wrong tier is a clean error, and the
// tiers are in --help METHOD and the output's history record.
#include "cli_runner.h"
#include "image_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

const std::string kSequence = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.####.exr";

/// Denoise frames 0-1 with `denoise` and read frame 1 back (empty pixels on failure).
ReadBack denoised(const TempDir& dir, const std::string& denoise, const std::string& name)
{
    const CliResult r = runAfntool({ "-q", "--frames", "0-1", kSequence, denoise, "-d", "float",
        "-o", dir.file(name + ".####.exr") });
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readImage(dir.file(name + ".0001.exr"));
}

double maxAbsDiff(const std::vector<float>& a, const std::vector<float>& b)
{
    if (a.size() != b.size() || a.empty())
        return -1.0;
    double m = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        m = std::max(m, static_cast<double>(std::abs(a[i] - b[i])));
    return m;
}

} // namespace

TEST(AfntoolQuality, AfnTiersAreDifferentResultsAndBalancedIsTheDefault)
{
    TempDir dir;
    const ReadBack plain = denoised(dir, "--denoise:method=afn", "plain");
    const ReadBack balanced = denoised(dir, "--denoise:method=afn:quality=balanced", "balanced");
    const ReadBack fast = denoised(dir, "--denoise:method=afn:quality=fast", "fast");
    const ReadBack high = denoised(dir, "--denoise:method=afn:quality=high", "high");
    ASSERT_FALSE(plain.pixels.empty());
    EXPECT_EQ(maxAbsDiff(balanced.pixels, plain.pixels), 0.0) << "balanced is today's afn";
    EXPECT_GT(maxAbsDiff(fast.pixels, plain.pixels), 1e-4);
    EXPECT_GT(maxAbsDiff(high.pixels, plain.pixels), 1e-4);
    EXPECT_GT(maxAbsDiff(high.pixels, fast.pixels), 1e-4);
    const std::string history = high.spec.get_string_attribute("Exif:ImageHistory");
    EXPECT_NE(history.find("quality=high"), std::string::npos) << history;
}

TEST(AfntoolQuality, OneLevelMethodsAcceptEveryTierWithTheSamePixels)
{
    TempDir dir;
    for (const std::string method : { "ta", "svgf", "bmfr" }) {
        const ReadBack plain = denoised(dir, "--denoise:method=" + method, method + "_plain");
        for (const std::string tier : { "fast", "high" }) {
            const ReadBack t = denoised(
                dir, "--denoise:method=" + method + ":quality=" + tier, method + "_" + tier);
            EXPECT_EQ(maxAbsDiff(t.pixels, plain.pixels), 0.0) << method << " " << tier;
        }
    }
}

TEST(AfntoolQuality, UnknownTierIsACleanErrorAndHelpListsTheTiers)
{
    TempDir dir;
    const CliResult bad = runAfntool({ "--frames", "0-1", kSequence,
        "--denoise:method=afn:quality=best", "-o", dir.file("x.####.exr") });
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_LT(bad.exitCode, 128);
    EXPECT_EQ(bad.err.rfind("afntool ERROR: ", 0), 0u) << bad.err;
    EXPECT_NE(bad.err.find("fast|balanced|high"), std::string::npos) << bad.err;
    EXPECT_TRUE(dir.entries().empty());

    const CliResult help = runAfntool({ "--help", "afn" });
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.out.find("quality"), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("refinement"), std::string::npos) << help.out;
    const CliResult svgfHelp = runAfntool({ "--help", "svgf" });
    EXPECT_NE(svgfHelp.out.find("one level"), std::string::npos) << svgfHelp.out;
}
