// SPDX-License-Identifier: Apache-2.0
// The AFN stripe path (methods/afn/network_stripes.cpp): bit-identical to the whole-frame stages
// for frames of one and of many stripes (odd sizes, both variants, 1 thread and all), also where a
// stripe takes input rows over from the previous one, and its work mask: stripes
// without work take the cheap path, the others are unchanged. The stripe plan depends on the
// thread count (near-equal stripes of at most 64 rows, their count a multiple of the threads):
// the tests that count stripes or reused rows run in an arena of a fixed size.
#include "afn_random_inputs.h"
#include "methods/afn/network.h"
#include "methods/afn/random_weights.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

using afn::Image;
using afn::afnet::Network;

namespace {

/// The network's inputs for these tests (seed 11).
struct Frame : afntest::RandomAfnInputs {
    Frame(int w, int h)
        : RandomAfnInputs(w, h, 11u)
    {
    }
};

int differingValues(const Image& a, const Image& b)
{
    EXPECT_TRUE(a.sameShape(b));
    int n = 0;
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
        n += a.data()[k] != b.data()[k];
    return n;
}

/// Random weights of `variant`; "trust" is full with the learned albedo trust (albedo_trust.h).
Network randomNetwork(const std::string& variant)
{
    afn::afnet::Architecture arch;
    arch.variant = variant == "trust" ? "full" : variant;
    arch.albedoTrust = variant == "trust";
    Network net;
    net.load(afn::afnet::randomWeights(arch, 3));
    return net;
}

} // namespace

TEST(AfnStripes, EqualWholeFramePathBitForBit)
{
    // One stripe (padded 40x24), and many: 203 rows pad to 208 = 26 blocks of 8 rows, at least
    // four stripes of at most 56 rows, so windows are clipped at the top, in the middle, and at
    // the bottom.
    for (const std::string variant : { "full", "fusion", "trust" })
        for (const auto& [w, h] : { std::pair { 37, 21 }, std::pair { 45, 203 } }) {
            Network net = randomNetwork(variant);
            Frame f(w, h);
            Image whole, striped, oneThread;
            net.runWholeFrame(f.in, whole);
            net.run(f.in, striped);
            EXPECT_GE(net.stripes(), h > 64 ? 4 : 1);
            EXPECT_EQ(differingValues(whole, striped), 0) << variant << " " << w << "x" << h;
            {
                tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                net.run(f.in, oneThread);
            }
            EXPECT_EQ(differingValues(whole, oneThread), 0) << variant << " 1 thread";
            // The stripe plan of other thread counts (3: stripes of unequal heights; 16: more
            // stripes than 203 rows make at 64, down to 8-16 rows each) gives the same bits.
            for (const int threads : { 3, 16 }) {
                Image planned;
                tbb::task_arena(threads).execute([&] { net.run(f.in, planned); });
                if (h > 64)
                    EXPECT_EQ(net.stripes(), threads == 3 ? 6 : 16);
                EXPECT_EQ(differingValues(whole, planned), 0) << variant << " " << threads;
            }
        }
}

TEST(AfnStripes, WorkspacesKeepNoTraceOfEarlierStripesOrFrames)
{
    // The stripe workspaces change shape between the first, inner and last stripes without being
    // cleared (Image::reshape): after frames of other contents and another size, on one thread
    // (one workspace through every shape) and on all, the result is the whole-frame path's.
    for (const std::string variant : { "full", "trust" }) {
        Network net = randomNetwork(variant);
        const afntest::RandomAfnInputs other(45, 203, 99u);
        const afntest::RandomAfnInputs big(61, 250, 7u);
        Frame f(45, 203);
        Image whole, scratch, striped;
        net.runWholeFrame(f.in, whole);
        for (const int threads : { 1, 0 }) {
            std::unique_ptr<tbb::global_control> limit;
            if (threads)
                limit = std::make_unique<tbb::global_control>(
                    tbb::global_control::max_allowed_parallelism, threads);
            net.run(other.in, scratch);
            net.run(big.in, scratch);
            net.run(f.in, striped);
            EXPECT_EQ(differingValues(whole, striped), 0) << variant << " threads " << threads;
        }
    }
}

TEST(AfnStripes, InputRowsTakenOverFromThePreviousStripeAreBitIdentical)
{
    // 330 rows pad to 336 = 42 blocks: on one thread six stripes of 56 rows, windows of up to
    // 120 rows, so a workspace that runs consecutive stripes moves the 64 input rows each window
    // shares with the last one instead of computing them (on one thread every stripe follows its
    // neighbour, whatever the windows' heights): 5 x 64 rows.
    // A second run of other inputs must not take rows over from the first. With the albedo trust
    // the colours are rescaled in place, so nothing is taken over.
    for (const std::string variant : { "full", "fusion", "trust" }) {
        const int reused = variant == "trust" ? 0 : 5 * 64;
        Network net = randomNetwork(variant);
        Frame f(29, 330);
        const afntest::RandomAfnInputs g(29, 330, 12u);
        Image whole, wholeG, striped, stripedG, again;
        net.runWholeFrame(f.in, whole);
        net.runWholeFrame(g.in, wholeG);
        tbb::task_arena(1).execute([&] {
            net.run(f.in, striped);
            EXPECT_EQ(net.stripes(), 6) << variant;
            EXPECT_EQ(net.inputRowsReused(), reused) << variant;
            net.run(g.in, stripedG);
            EXPECT_EQ(net.inputRowsReused(), reused) << variant;
        });
        EXPECT_EQ(differingValues(whole, striped), 0) << variant;
        EXPECT_EQ(differingValues(wholeG, stripedG), 0) << variant << " second inputs";
        net.run(f.in, again); // all threads: whatever is taken over, the same values
        EXPECT_EQ(differingValues(whole, again), 0) << variant << " all threads";
    }
}

TEST(AfnStripes, WorkMaskSkipsStripesWithoutWorkOnly)
{
    const int w = 33, h = 300, masked = h * 60 / 100; // top 60 % masked out
    Network net = randomNetwork("full");
    Frame f(w, h);
    Image plain, skipped;
    net.run(f.in, plain);
    EXPECT_EQ(net.skippedRows(), 0);
    Image work(w, h, 1, 1.0f);
    std::fill(work.data(), work.at(0, masked), 0.0f);
    net.run(f.in, skipped, &work);
    // Rows 0-179 masked: the 8-row blocks up to row 175 have no work; block [176, 184) has rows
    // 180+, so the network computes padded rows [176, 304): on 2 threads stripes [176, 240),
    // [240, 304), on 4 four of 32 rows.
    EXPECT_EQ(net.skippedRows(), 176);
    for (const int threads : { 2, 4 }) {
        Image again;
        tbb::task_arena(threads).execute([&] { net.run(f.in, again, &work); });
        EXPECT_EQ(net.stripes(), threads);
        EXPECT_EQ(differingValues(skipped, again), 0) << threads << " threads";
    }
    int differ = 0, notCheap = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                if (y >= masked)
                    differ += skipped(x, y, c) != plain(x, y, c);
                if (y < 176)
                    notCheap += skipped(x, y, c) != f.cta(x, y, c);
            }
    EXPECT_EQ(differ, 0) << "pixels with work differ from the run without mask";
    EXPECT_EQ(notCheap, 0) << "skipped pixels are not the temporal accumulation";
    // All ones, or an empty mask, is no mask.
    Image ones(w, h, 1, 1.0f), none, again;
    net.run(f.in, again, &ones);
    EXPECT_EQ(differingValues(plain, again), 0);
    net.run(f.in, again, &none);
    EXPECT_EQ(differingValues(plain, again), 0);
}

TEST(AfnStripes, WorkMaskRunsOffTheStripeGridAreBitIdentical)
{
    // Two bands of work, neither on the 64-row grid: rows 100-169 (blocks [96, 176): on 2 threads
    // stripes [96, 136), [136, 176)) and rows 250-252 (block [248, 256): one stripe); the rows
    // between are cheap.
    const int w = 41, h = 300;
    Network net = randomNetwork("full");
    Frame f(w, h);
    Image plain, skipped;
    net.run(f.in, plain);
    Image work(w, h, 1, 0.0f);
    for (int y = 100; y < 170; ++y)
        work(y % w, y, 0) = 1.0f; // one pixel a row marks the row
    for (int y = 250; y < 253; ++y)
        work(0, y, 0) = 1.0f;
    tbb::task_arena(2).execute([&] { net.run(f.in, skipped, &work); });
    EXPECT_EQ(net.stripes(), 3);
    EXPECT_EQ(net.skippedRows(), h - 80 - 8);
    int differ = 0, notCheap = 0;
    for (int y = 0; y < h; ++y) {
        const bool computed = (y >= 96 && y < 176) || (y >= 248 && y < 256);
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                (computed ? differ : notCheap)
                    += skipped(x, y, c) != (computed ? plain(x, y, c) : f.cta(x, y, c));
    }
    EXPECT_EQ(differ, 0) << "computed rows differ from the run without mask";
    EXPECT_EQ(notCheap, 0) << "rows without work are not the temporal accumulation";
}

TEST(AfnStripes, RejectsAWorkMaskOfAnotherSize)
{
    Network net = randomNetwork("full");
    Frame f(16, 16);
    Image out, work(16, 15, 1, 1.0f);
    EXPECT_ANY_THROW(net.run(f.in, out, &work));
}
