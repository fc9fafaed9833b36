// SPDX-License-Identifier: Apache-2.0
// The AFN stripe path (methods/afn/network_stripes.cpp): bit-identical to the whole-frame stages
// for frames of one and of many stripes (odd sizes, both variants, 1 thread and all), and its work
// mask (issue 19): stripes without work take the cheap path, the others are unchanged.
#include "methods/afn/network.h"
#include "methods/afn/random_weights.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <random>

using afn::Image;
using afn::afnet::Network;

namespace {

struct Frame {
    Image c1, cta, albedo, normal, depth;
    afn::afnet::Inputs in;
    Frame(int w, int h)
    {
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        auto fill = [&](Image& img, int c, float scale) {
            img = Image(w, h, c);
            for (std::size_t k = 0; k < img.size(); ++k)
                img.data()[k] = scale * u(rng);
        };
        fill(c1, 3, 4.0f), fill(cta, 3, 2.0f), fill(albedo, 3, 1.0f), fill(normal, 3, 1.0f);
        fill(depth, 1, 1.0f);
        in = { &c1, &cta, &albedo, &normal, &depth };
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

Network randomNetwork(const std::string& variant)
{
    afn::afnet::Architecture arch;
    arch.variant = variant;
    Network net;
    net.load(afn::afnet::randomWeights(arch, 3));
    return net;
}

} // namespace

TEST(AfnStripes, EqualWholeFramePathBitForBit)
{
    // One stripe (padded 40x24), and many: 203 rows pad to 208 = 3 stripes of 64 and one of 16,
    // so windows are clipped at the top, in the middle, and at the bottom.
    for (const std::string variant : { "full", "fusion" })
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
        }
}

TEST(AfnStripes, WorkMaskSkipsStripesWithoutWorkOnly)
{
    const int w = 33, h = 300, masked = h * 60 / 100; // top 60 % masked out
    Network net = randomNetwork("full");
    Frame f(w, h);
    Image plain, skipped;
    net.run(f.in, plain);
    EXPECT_EQ(net.skippedStripes(), 0);
    Image work(w, h, 1, 1.0f);
    std::fill(work.data(), work.at(0, masked), 0.0f);
    net.run(f.in, skipped, &work);
    // Rows 0-179 masked: stripes [0, 64) and [64, 128) have no work; [128, 192) has rows 180+.
    EXPECT_EQ(net.skippedStripes(), 2);
    EXPECT_EQ(net.stripes(), 5);
    int differ = 0, notCheap = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                if (y >= masked)
                    differ += skipped(x, y, c) != plain(x, y, c);
                if (y < 128)
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

TEST(AfnStripes, RejectsAWorkMaskOfAnotherSize)
{
    Network net = randomNetwork("full");
    Frame f(16, 16);
    Image out, work(16, 15, 1, 1.0f);
    EXPECT_ANY_THROW(net.run(f.in, out, &work));
}
