// SPDX-License-Identifier: Apache-2.0
// afntool on files, end to end (the real binary):
//   - every method's output sequence is bit-identical with --threads 1, --threads 2 and a repeat
//     (the pixels: the files differ in their capDate header attribute);
//   - a truncated or corrupt frame in the middle of a sequence stops afntool with
//     "afntool ERROR: ..." naming that frame, the outputs of the earlier frames are intact and
//     nothing else (no later frame, no temporary file) is left in the output folder;
//   - values beyond the half range come out finite when written as half, NaN input is reported.
#include "cli_runner.h"
#include "exr_sequence.h"

#include <afn/io.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

using namespace stress;
namespace fs = std::filesystem;

namespace {

std::vector<FrameData> frames(int n, int w = 24, int h = 14)
{
    std::vector<FrameData> out;
    for (int f = 0; f < n; ++f)
        out.push_back(plausibleFrame(w, h, f, 3));
    return out;
}

std::vector<std::string> sorted(std::vector<std::string> v)
{
    std::sort(v.begin(), v.end());
    return v;
}

TEST(AfntoolFiles, EveryMethodIsBitIdenticalForAnyThreadCount)
{
    TempDir dir;
    writeExrSequence(dir.file("in.%04d.exr"), frames(4));
    for (const std::string& method : allMethods()) {
        SCOPED_TRACE(method);
        std::vector<std::string> runs;
        for (const char* threads : { "1", "2", "2" }) {
            const std::string out = dir.file(
                method + "_t" + threads + "_" + std::to_string(runs.size()) + ".####.exr");
            const CliResult r
                = runAfntool({ "--threads", threads, "--frames", "0-3", dir.file("in.####.exr"),
                    "--denoise:method=" + method, "-d", "float", "-o", out, "--quiet" });
            ASSERT_EQ(r.exitCode, 0) << r.err;
            runs.push_back(out);
        }
        for (int f = 0; f < 4; ++f) {
            const std::string first = afn::io::expandFramePattern(runs[0], f);
            const std::vector<float> a = readColor(first);
            for (std::size_t k = 1; k < runs.size(); ++k) {
                const std::string other = afn::io::expandFramePattern(runs[k], f);
                std::string where;
                EXPECT_TRUE(bitIdentical(a, readColor(other), &where)) << other << ": " << where;
            }
        }
    }
}

/// Ways a farm node can leave a frame behind.
struct Damage {
    const char* name;
    void (*apply)(const std::string& path);
};

void truncateTo(const std::string& path, double fraction)
{
    const std::string bytes = fileBytes(path);
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size() * fraction));
}

const Damage kDamages[] = {
    { "truncated to half", [](const std::string& p) { truncateTo(p, 0.5); } },
    { "truncated in the header", [](const std::string& p) { truncateTo(p, 0.02); } },
    { "empty", [](const std::string& p) { truncateTo(p, 0.0); } },
    { "pixel data overwritten",
        [](const std::string& p) {
            std::string bytes = fileBytes(p);
            for (std::size_t i = bytes.size() / 2; i < bytes.size() - 16; ++i)
                bytes[i] = static_cast<char>(i * 37);
            std::ofstream(p, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
        } },
    { "not an image",
        [](const std::string& p) {
            std::ofstream(p, std::ios::binary | std::ios::trunc) << "render node died\n";
        } },
};

TEST(AfntoolFiles, CorruptFrameInTheMiddleIsNamedAndEarlierOutputsStayIntact)
{
    for (const Damage& damage : kDamages) {
        SCOPED_TRACE(damage.name);
        TempDir in, clean, out;
        const std::vector<std::string> inputs
            = writeExrSequence(in.file("shot.%04d.exr"), frames(5));
        const std::vector<std::string> args
            = { "--frames", "0-4", in.file("shot.####.exr"), "--denoise:method=ta", "-o" };
        CliResult r = runAfntool(
            { args[0], args[1], args[2], args[3], args[4], clean.file("out.####.exr"), "--quiet" });
        ASSERT_EQ(r.exitCode, 0) << r.err;

        damage.apply(inputs[2]);
        const std::string damaged = fileBytes(inputs[2]);
        r = runAfntool(
            { args[0], args[1], args[2], args[3], args[4], out.file("out.####.exr"), "--quiet" });
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(r.err.rfind("afntool ERROR: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(inputs[2]), std::string::npos) << "the frame is not named: " << r.err;
        EXPECT_EQ(r.err.find(inputs[1]), std::string::npos) << r.err;
        EXPECT_EQ(
            sorted(out.entries()), (std::vector<std::string> { "out.0000.exr", "out.0001.exr" }));
        for (const char* name : { "out.0000.exr", "out.0001.exr" }) {
            std::string where;
            EXPECT_TRUE(
                bitIdentical(readColor(out.file(name)), readColor(clean.file(name)), &where))
                << name << ": " << where;
        }
        EXPECT_TRUE(fileBytes(inputs[2]) == damaged) << "afntool changed its input";
    }
}

TEST(AfntoolFiles, FrameOfAnotherSizeInTheMiddleIsNamed)
{
    TempDir in, out;
    std::vector<FrameData> seq = frames(4);
    seq[2] = plausibleFrame(20, 14, 2);
    const std::vector<std::string> inputs = writeExrSequence(in.file("shot.%04d.exr"), seq);
    const CliResult r = runAfntool({ "--frames", "0-3", in.file("shot.####.exr"),
        "--denoise:method=svgf", "-o", out.file("out.####.exr"), "--quiet" });
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err.rfind("afntool ERROR: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(inputs[2]), std::string::npos) << r.err;
    EXPECT_EQ(sorted(out.entries()), (std::vector<std::string> { "out.0000.exr", "out.0001.exr" }));
}

TEST(AfntoolFiles, HalfOutputOfValuesBeyondTheHalfRangeStaysFinite)
{
    TempDir dir;
    FrameData f = plausibleFrame(16, 8, 0);
    f.plane("color")[3 * 20 + 0] = 1e6f;
    f.plane("color")[3 * 21 + 1] = 70000.0f;
    f.plane("color")[3 * 22 + 2] = std::nanf("");
    writeExr(dir.file("in.exr"), f);
    const CliResult r = runAfntool({ dir.file("in.exr"), "--denoise:method=identity", "-d", "half",
        "-o", dir.file("half.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("1 NaN/Inf input values replaced"), std::string::npos) << r.err;
    const std::vector<float> half = readColor(dir.file("half.exr"));
    std::string where;
    EXPECT_TRUE(allFinite(half, &where)) << where;
    EXPECT_EQ(*std::max_element(half.begin(), half.end()), 65504.0f);
    // As float the values are kept.
    ASSERT_EQ(runAfntool({ dir.file("in.exr"), "--denoise:method=identity", "-d", "float", "-o",
                             dir.file("float.exr"), "--quiet" })
                  .exitCode,
        0);
    const std::vector<float> full = readColor(dir.file("float.exr"));
    EXPECT_EQ(full[3 * 20], 1e6f);
    EXPECT_EQ(full[3 * 22 + 2], 0.0f);
}

} // namespace
