// SPDX-License-Identifier: Apache-2.0
// Frame ranges and file-name patterns in oiiotool's conventions.
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "test_io_util.h"

using namespace afn::io;
using V = std::vector<int>;

TEST(IoSequence, Ranges)
{
    EXPECT_EQ(parseFrameRange("1-4"), (V { 1, 2, 3, 4 }));
    EXPECT_EQ(parseFrameRange("1-10x3"), (V { 1, 4, 7, 10 }));
    EXPECT_EQ(parseFrameRange("1-9x4"), (V { 1, 5, 9 }));
    EXPECT_EQ(parseFrameRange("3,5,7"), (V { 3, 5, 7 }));
    EXPECT_EQ(parseFrameRange("1-3,10"), (V { 1, 2, 3, 10 }));
    EXPECT_EQ(parseFrameRange("7"), (V { 7 }));
    EXPECT_EQ(parseFrameRange("4-2"), (V { 4, 3, 2 }));
    EXPECT_EQ(parseFrameRange("-2-1"), (V { -2, -1, 0, 1 }));
    for (const char* bad : { "", "a", "1-", "1-5x0", "1-5x", "1,,2", "1-2-3", "1..3", "5x2" })
        EXPECT_THROW(parseFrameRange(bad), IoError) << bad;
}

TEST(IoSequence, Patterns)
{
    EXPECT_TRUE(hasFramePattern("shot.####.exr"));
    EXPECT_TRUE(hasFramePattern("shot.@@.exr"));
    EXPECT_TRUE(hasFramePattern("shot.%04d.exr"));
    EXPECT_TRUE(hasFramePattern("shot.%d.exr"));
    EXPECT_FALSE(hasFramePattern("shot.0001.exr"));
    EXPECT_FALSE(hasFramePattern("100%.exr"));
    EXPECT_EQ(expandFramePattern("shot.####.exr", 7), "shot.0007.exr");
    EXPECT_EQ(expandFramePattern("shot.#.exr", 7), "shot.0007.exr"); // a lone '#' is 4 digits
    EXPECT_EQ(expandFramePattern("shot.##.exr", 7), "shot.07.exr"); // runs: one digit each
    EXPECT_EQ(expandFramePattern("shot.@@@.exr", 7), "shot.007.exr");
    EXPECT_EQ(expandFramePattern("shot.@.exr", 12), "shot.12.exr");
    EXPECT_EQ(expandFramePattern("shot.%03d.exr", 12), "shot.012.exr");
    EXPECT_EQ(expandFramePattern("shot.%d.exr", 12), "shot.12.exr");
    EXPECT_EQ(expandFramePattern("shot.####.exr", 12345), "shot.12345.exr");
    EXPECT_EQ(expandFramePattern("shot.####.exr", -7), "shot.-007.exr"); // printf width
    EXPECT_EQ(expandFramePattern("d####/f####.exr", 3), "d0003/f0003.exr");
}

TEST(IoSequence, ExpandChecksEveryFrame)
{
    afn_test::ScratchDir dir;
    for (int f : { 1, 2, 4 })
        std::ofstream(dir.file("f." + std::to_string(f) + ".exr")) << "x";
    const std::string pattern = dir.file("f.@.exr");
    EXPECT_EQ(expandSequence(pattern, { 1, 2 }),
        (std::vector<std::string> { dir.file("f.1.exr"), dir.file("f.2.exr") }));
    try {
        expandSequence(pattern, { 1, 2, 3, 4 });
        FAIL() << "missing frame accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("frame 3"), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), dir.file("f.3.exr"));
    }
    EXPECT_EQ(expandSequence(pattern, { 3 }, false).size(), 1u);
    EXPECT_THROW(expandSequence(dir.file("plain.exr"), { 1 }), IoError);
}
