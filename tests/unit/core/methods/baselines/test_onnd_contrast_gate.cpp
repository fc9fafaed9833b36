// SPDX-License-Identifier: Apache-2.0
// ONND's local-contrast gate (methods/onnd/contrast_gate.h): exactly 0 on a flat or black window,
// fully open on noise, the formula on a step; and through the network with random-initialised
// weights (the parity archive): a constant or black frame comes back bit for bit, frame after
// frame, whatever the recurrent state (the stress properties by construction).
#include "afn_test_util.h"
#include "methods/onnd/contrast_gate.h"
#include "methods/onnd/network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace {

float maxOf(const afn::Image& img)
{
    return *std::max_element(img.data(), img.data() + img.size());
}

} // namespace

TEST(OnndContrastGate, FlatAndBlackWindowsGiveExactlyZero)
{
    afn::Image gate;
    for (const float v : { 0.0f, 1e-30f, 1e-3f, 0.37f, 3.0f, 1e30f }) {
        afn::onnd::contrastGate(afn::Image(9, 7, 3, v), gate);
        EXPECT_EQ(maxOf(gate), 0.0f) << v;
    }
    afn::onnd::contrastGate(afn::Image(9, 7, 3, -2.0f), gate); // negatives read as 0
    EXPECT_EQ(maxOf(gate), 0.0f);
}

TEST(OnndContrastGate, NoiseOpensTheGateFully)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.7f, 1.3f); // +-30 %, far less than 1-spp noise
    afn::Image c(16, 12, 3), gate;
    for (std::size_t k = 0; k < c.size(); ++k)
        c.data()[k] = u(rng);
    afn::onnd::contrastGate(c, gate);
    ASSERT_EQ(gate.channels(), 1);
    EXPECT_EQ(*std::min_element(gate.data(), gate.data() + gate.size()), 1.0f);
}

TEST(OnndContrastGate, StepFollowsTheFormula)
{
    // Columns < 5 at 1.0, the rest at 1.05 in the green channel only: the gate is nonzero only
    // in the two columns whose 3x3 window straddles the step, partial there (the gain times
    // the relative range), and zero elsewhere.
    afn::Image c(10, 4, 3, 1.0f), gate;
    for (int y = 0; y < 4; ++y)
        for (int x = 5; x < 10; ++x)
            c(x, y, 1) = 1.05f;
    afn::onnd::contrastGate(c, gate);
    const float want = std::min(
        afn::onnd::kGateGain * (1.05f - 1.0f) / (1.05f + 1.0f + afn::onnd::kGateEps), 1.0f);
    ASSERT_GT(want, 0.0f);
    ASSERT_LT(want, 1.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 10; ++x)
            EXPECT_FLOAT_EQ(gate(x, y, 0), (x == 4 || x == 5) ? want : 0.0f) << x << "," << y;
}

TEST(OnndContrastGate, NetworkReturnsFlatFramesBitForBit)
{
    afn::onnd::Network net;
    net.load(afntest::loadFile(std::string(AFN_TEST_DATA) + "/baselines_parity/onnd_weights.afnw"));
    const int w = 37, h = 21;
    const afn::Image albedo(w, h, 3, 0.5f), normal(w, h, 3, 0.5f), depth(w, h, 1, 0.3f);
    afn::Image out;
    for (const float v : { 0.0f, 1e-3f, 0.37f, 3.0f }) {
        const afn::Image cta(w, h, 3, v);
        net.resetState();
        for (int frame = 0; frame < 5; ++frame) { // the recurrent state changes, the output not
            net.run({ &cta, &albedo, &normal, &depth }, out);
            ASSERT_EQ(out.size(), cta.size());
            for (std::size_t k = 0; k < out.size(); ++k)
                ASSERT_EQ(out.data()[k], v) << "value " << v << " frame " << frame << " at " << k;
        }
    }
    // A noisy frame does go through the network (the gate is not simply closed).
    afn::Image noisy(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k)
                noisy(x, y, k) = static_cast<float>((x * 7 + y * 3 + k) % 5) * 0.3f;
    net.resetState();
    net.run({ &noisy, &albedo, &normal, &depth }, out);
    double diff = 0.0;
    for (std::size_t k = 0; k < out.size(); ++k)
        diff = std::max(diff, static_cast<double>(std::fabs(out.data()[k] - noisy.data()[k])));
    EXPECT_GT(diff, 1e-3);
}
