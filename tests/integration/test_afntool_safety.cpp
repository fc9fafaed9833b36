// SPDX-License-Identifier: Apache-2.0
// afntool never writes over a file it reads (inputs, --compare references, weights; by inode and
// canonical path, through symlinks and frame patterns), checks --compression against the output
// format, and handles frame ranges as oiiotool does (negative frames) or refuses them with a
// reason (descending frames for temporal methods, --frames on a single file).
#include "cli_runner.h"

#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const std::string kSequence = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.####.exr";
const std::string kFrame0 = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.0000.exr";
const std::string kFrame1 = std::string(AFN_EXAMPLES_DIR) + "/sequence/frame.0001.exr";

std::string contents(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void expectRefused(const CliResult& r, const std::string& needle)
{
    EXPECT_NE(r.exitCode, 0);
    EXPECT_LT(r.exitCode, 128) << "killed by a signal";
    EXPECT_EQ(r.err.rfind("afntool ERROR: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

TEST(AfntoolSafety, NeverOverwritesAReferenceOrWeights)
{
    TempDir dir;
    const std::string in = dir.file("in.exr"), ref = dir.file("ref.exr");
    fs::copy_file(kFrame0, in);
    fs::copy_file(kFrame1, ref);
    const std::string before = contents(ref);

    expectRefused(runAfntool({ in, "--compare", ref, "-o", ref }),
        "-o would overwrite the --compare reference");
    // The same file under another spelling, through a symlink and through a hard link.
    fs::create_directory(dir.file("sub"));
    fs::create_symlink(ref, dir.file("link.exr"));
    fs::create_hard_link(ref, dir.file("hard.exr"));
    for (const std::string& out :
        { dir.file("sub/../ref.exr"), dir.file("link.exr"), dir.file("hard.exr") })
        expectRefused(runAfntool({ in, "--compare", ref, "-o", out }), "--compare reference");
    // The reference given through the symlink, the output by its real name.
    expectRefused(runAfntool({ in, "--compare", dir.file("link.exr"), "--preview", ref }),
        "--preview would overwrite");
    EXPECT_EQ(contents(ref), before);

    // Weights files are read too.
    const std::string weights = dir.file("w.afnw");
    fs::copy_file(std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw", weights);
    const std::string w0 = contents(weights);
    expectRefused(runAfntool({ in, "--weights", weights, "--denoise:method=afn", "-o", weights }),
        "the weights file");
    expectRefused(
        runAfntool({ in, "--denoise:method=afn:weights=" + weights, "--preview", weights }),
        "the weights file");
    EXPECT_EQ(contents(weights), w0);
}

TEST(AfntoolSafety, NeverOverwritesThroughFramePatterns)
{
    TempDir dir;
    for (const char* f : { "0000", "0001" }) {
        fs::copy_file(std::string(AFN_EXAMPLES_DIR) + "/sequence/frame." + f + ".exr",
            dir.file(std::string("ref.") + f + ".exr"));
    }
    const std::string before = contents(dir.file("ref.0001.exr"));
    // Frame 0's output is fine, frame 1's is the reference of frame 1: refused before anything
    // is written.
    expectRefused(runAfntool({ "--frames", "0-1", kSequence, "--compare", dir.file("ref.####.exr"),
                      "-o", dir.file("ref.%04d.exr") }),
        "--compare reference");
    EXPECT_EQ(contents(dir.file("ref.0001.exr")), before);
    EXPECT_EQ(dir.entries().size(), 2u) << "nothing written";
    // An output pattern naming another frame of the input sequence.
    fs::copy_file(kFrame0, dir.file("in.0000.exr"));
    fs::copy_file(kFrame1, dir.file("in.0001.exr"));
    expectRefused(
        runAfntool({ "--frames", "0-1", dir.file("in.####.exr"), "-o", dir.file("in.@@@@.exr") }),
        "an input");
}

TEST(AfntoolSafety, CompressionIsCheckedAgainstTheFormat)
{
    TempDir dir;
    const CliResult r = runAfntool({ kFrame0, "--compression", "lzma", "-o", dir.file("o.exr") });
    expectRefused(r,
        "--compression lzma is not available for openexr files (valid: none, rle, "
        "zips, zip, piz,");
    expectRefused(runAfntool({ kFrame0, "--compression", "piz", "-o", dir.file("o.hdr") }),
        "no compression choices");
    EXPECT_EQ(dir.entries().size(), 0u);
    const CliResult ok = runAfntool({ kFrame0, "--compression", "piz", "-o", dir.file("o.exr") });
    ASSERT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_EQ(afn::io::inspect(dir.file("o.exr")).subimages[0].compression, "piz");
}

TEST(AfntoolSafety, NegativeFrameNumbers)
{
    TempDir dir;
    // Frame numbers padded as oiiotool writes them: the width includes the sign ("-001").
    fs::copy_file(kFrame0, dir.file("neg.-001.exr"));
    fs::copy_file(kFrame0, dir.file("neg.0000.exr"));
    fs::copy_file(kFrame1, dir.file("neg.0001.exr"));
    const CliResult r = runAfntool({ "--frames", "-1-1", dir.file("neg.####.exr"),
        "--denoise:method=ta", "-o", dir.file("out.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : { "out.-001.exr", "out.0000.exr", "out.0001.exr" })
        EXPECT_TRUE(fs::exists(dir.file(f))) << f;
    const CliResult only = runAfntool(
        { "--frames", "-1--1", dir.file("neg.####.exr"), "-o", dir.file("one.%04d.exr") });
    ASSERT_EQ(only.exitCode, 0) << only.err;
    EXPECT_TRUE(fs::exists(dir.file("one.-001.exr")));
}

TEST(AfntoolSafety, DescendingFramesAreRefusedForTemporalMethods)
{
    TempDir dir;
    expectRefused(runAfntool({ "--frames", "1-0", kSequence, "--denoise:method=svgf", "-o",
                      dir.file("o.####.exr") }),
        "--frames 1-0 is not in ascending order, but --denoise:method=svgf is temporal");
    expectRefused(
        runAfntool({ "--frames", "0,1,0", kSequence, "--features", dir.file("f.####.exr") }),
        "ascending order");
    EXPECT_EQ(dir.entries().size(), 0u);
    // A method without history may run in any order.
    const CliResult r = runAfntool({ "--frames", "1-0", kSequence, "--denoise:method=identity",
        "-o", dir.file("i.####.exr") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(AfntoolSafety, FramesOnASingleFileIsAnError)
{
    TempDir dir;
    expectRefused(runAfntool({ "--frames", "0-3", kFrame0, "-o", dir.file("o.exr") }),
        "needs a frame pattern in the input name");
    EXPECT_EQ(dir.entries().size(), 0u);
}

} // namespace
