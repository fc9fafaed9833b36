// SPDX-License-Identifier: Apache-2.0
// AFN's quality tiers (methods/afn/quality_tiers.h) on the committed "full" parity weights at an
// odd size (19 x 11, padded to 24 x 16): balanced is Network::run; fast is the fused output before
// the refinement; high is the mean of the four flipped passes flipped back (checked against the
// test's own flips), so it commutes with flipping the input; stage totals count every pass.
#include "afn_test_util.h"
#include "methods/afn/quality_tiers.h"
#include "stages/demodulate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using afn::Image;
using afn::afnet::Inputs;
using afn::afnet::Network;
using afn::afnet::TierRunner;
using Tier = afn::QualitySettings::Tier;

constexpr int kW = 19, kH = 11;

struct Frame {
    Image c1 { kW, kH, 3 }, cta { kW, kH, 3 }, albedo { kW, kH, 3 }, normal { kW, kH, 3 },
        depth { kW, kH, 1 };
    Inputs inputs() const { return { &c1, &cta, &albedo, &normal, &depth }; }
};

/// A frame without any mirror symmetry (x and y enter differently in every channel).
Frame asymmetricFrame()
{
    Frame f;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            for (int c = 0; c < 3; ++c) {
                f.c1(x, y, c) = static_cast<float>((x * 7 + y * 13 + c * 5) % 11) * 0.2f;
                f.cta(x, y, c) = 0.3f + 0.05f * static_cast<float>(x + 2 * y + c);
                f.albedo(x, y, c) = 0.2f + 0.03f * static_cast<float>((x * y + c) % 20);
                f.normal(x, y, c) = c == 2 ? 1.0f : 0.5f + 0.02f * static_cast<float>(x - y);
            }
            f.depth(x, y, 0) = static_cast<float>(x * x + 3 * y) / (kW * kW + 3.0f * kH);
        }
    return f;
}

/// The test's own mirror: (x, y) <- (W-1-x or x, H-1-y or y).
Image mirrored(const Image& src, bool fx, bool fy)
{
    Image d(src.width(), src.height(), src.channels());
    for (int y = 0; y < src.height(); ++y)
        for (int x = 0; x < src.width(); ++x)
            for (int c = 0; c < src.channels(); ++c)
                d(x, y, c) = src(fx ? src.width() - 1 - x : x, fy ? src.height() - 1 - y : y, c);
    return d;
}

Frame mirroredFrame(const Frame& f, bool fx, bool fy)
{
    return { mirrored(f.c1, fx, fy), mirrored(f.cta, fx, fy), mirrored(f.albedo, fx, fy),
        mirrored(f.normal, fx, fy), mirrored(f.depth, fx, fy) };
}

double maxAbsDiff(const Image& a, const Image& b)
{
    double m = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        m = std::max(m, std::fabs(static_cast<double>(a.data()[i]) - b.data()[i]));
    return m;
}

Network fullNetwork()
{
    Network net;
    net.load(afntest::loadFile(std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw"));
    return net;
}

} // namespace

TEST(AfnQuality, BalancedIsTheNetworkAsTrained)
{
    Network net = fullNetwork();
    const Frame f = asymmetricFrame();
    Image expected, got;
    net.run(f.inputs(), expected);
    TierRunner tiers;
    tiers.run(Tier::Balanced, net, f.inputs(), got);
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(maxAbsDiff(got, expected), 0.0) << "bit-identical";
    for (int k = 0; k < Network::kStages; ++k)
        EXPECT_EQ(tiers.totals().flop[k], net.stageFlop(static_cast<Network::Stage>(k)));
}

TEST(AfnQuality, FastIsTheFusedOutputWithoutRefinement)
{
    Network net = fullNetwork();
    const Frame f = asymmetricFrame();
    Image balanced, fast;
    net.runWholeFrame(f.inputs(), balanced); // fused() is kept by the whole-frame path only
    const Image fused = net.fused(); // padded; the refinement's input
    TierRunner tiers;
    tiers.run(Tier::Fast, net, f.inputs(), fast);
    ASSERT_EQ(fast.width(), kW);
    ASSERT_EQ(fast.height(), kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(fast(x, y, c), fused(x, y, c)) << x << "," << y;
    EXPECT_GT(maxAbsDiff(fast, balanced), 1e-4) << "the refinement must have been skipped";
    const int refinement = static_cast<int>(Network::Stage::Refinement);
    EXPECT_EQ(tiers.totals().flop[refinement], 0.0);
    EXPECT_EQ(tiers.totals().ms[refinement], 0.0);
    EXPECT_GT(tiers.totals().flop[0], 0.0);
}

// With the learned albedo trust the fused image is taken back to the albedo-demodulated space
// (divided by s = max(a, eps) / max(a + (1 - a) t, eps)) over the frame's own width: the padded
// columns are cropped, not written past the output's rows.
TEST(AfnQuality, FastWithTheAlbedoTrustIsTheFusedOutputOutOfItsSpace)
{
    Network net;
    net.load(afntest::loadFile(std::string(AFN_TEST_DATA) + "/afn_parity/weights_trust.afnw"));
    ASSERT_TRUE(net.hasAlbedoTrust());
    const Frame f = asymmetricFrame();
    const Image history01(kW, kH, 1, 0.5f);
    Inputs in = f.inputs();
    in.history01 = &history01;
    Image balanced, fast;
    net.runWholeFrame(in, balanced);
    const Image fused = net.fused(), trust = net.albedoTrust();
    TierRunner tiers;
    tiers.run(Tier::Fast, net, in, fast);
    ASSERT_EQ(fast.width(), kW);
    ASSERT_EQ(fast.height(), kH);
    const float eps = afn::kAlbedoEpsilon;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) {
                const float a = f.albedo(x, y, c), t = trust(x / 2, y / 2, 0);
                const float s = std::max(a, eps) / std::max(a + (1.0f - a) * t, eps);
                ASSERT_EQ(fast(x, y, c), fused(x, y, c) / s) << x << "," << y;
            }
}

TEST(AfnQuality, HighAveragesTheFourFlipsFlippedBack)
{
    Network net = fullNetwork();
    const Frame f = asymmetricFrame();
    Image expected(kW, kH, 3), pass, high;
    for (int k = 0; k < 4; ++k) {
        const bool fx = (k & 1) != 0, fy = (k & 2) != 0;
        const Frame m = mirroredFrame(f, fx, fy);
        net.run(m.inputs(), pass);
        const Image back = mirrored(pass, fx, fy);
        for (std::size_t i = 0; i < expected.size(); ++i)
            expected.data()[i] += 0.25f * back.data()[i];
    }
    TierRunner tiers;
    tiers.run(Tier::High, net, f.inputs(), high);
    EXPECT_LT(maxAbsDiff(high, expected), 1e-5);
    Image balanced;
    net.run(f.inputs(), balanced);
    EXPECT_GT(maxAbsDiff(high, balanced), 1e-4) << "the ensemble must differ from one pass";
    for (int k = 0; k < Network::kStages; ++k)
        EXPECT_DOUBLE_EQ(
            tiers.totals().flop[k], 4.0 * net.stageFlop(static_cast<Network::Stage>(k)));
}

TEST(AfnQuality, HighCommutesWithFlippingTheInput)
{
    // The one-pass network does not (its 2x2 pooling and padding are anchored top-left); the
    // ensemble over the flip group does, up to the order of the four-term sum.
    Network net = fullNetwork();
    const Frame f = asymmetricFrame();
    TierRunner tiers;
    for (int k = 1; k < 4; ++k) {
        const bool fx = (k & 1) != 0, fy = (k & 2) != 0;
        Image high, highOfMirror, balanced, balancedOfMirror;
        tiers.run(Tier::High, net, f.inputs(), high);
        tiers.run(Tier::High, net, mirroredFrame(f, fx, fy).inputs(), highOfMirror);
        EXPECT_LT(maxAbsDiff(mirrored(highOfMirror, fx, fy), high), 1e-5) << k;
        net.run(f.inputs(), balanced);
        net.run(mirroredFrame(f, fx, fy).inputs(), balancedOfMirror);
        EXPECT_GT(maxAbsDiff(mirrored(balancedOfMirror, fx, fy), balanced), 1e-4) << k;
    }
}

TEST(AfnQuality, FlipImageMirrorsEveryChannel)
{
    Image src(3, 2, 2), dst;
    for (std::size_t i = 0; i < src.size(); ++i)
        src.data()[i] = static_cast<float>(i);
    afn::afnet::flipImage(src, true, false, dst);
    EXPECT_EQ(dst(0, 0, 0), src(2, 0, 0));
    EXPECT_EQ(dst(0, 0, 1), src(2, 0, 1));
    afn::afnet::flipImage(src, false, true, dst);
    EXPECT_EQ(dst(2, 0, 1), src(2, 1, 1));
    afn::afnet::flipImage(src, true, true, dst);
    EXPECT_EQ(dst(0, 1, 0), src(2, 0, 0));
    EXPECT_EQ(maxAbsDiff(mirrored(src, true, true), dst), 0.0);
}
