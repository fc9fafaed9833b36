// SPDX-License-Identifier: Apache-2.0
// PyTorch <-> C++ parity of the learned baselines ONND and MR-KP: the committed vectors of
// tests/data/baselines_parity (regenerate with
// `cd training && /usr/bin/python3 -m afn.baselines.onnd_mrkp_parity_vectors`) through the C++
// engines. A 37x21 frame (padding rule covered), random-initialised narrow weights; ONND over three
// frames so the recurrent state is compared too. The tolerance is float rounding (different
// summation orders, exp/pow implementations).
#include "afn_test_util.h"
#include "base/exception.h"
#include "methods/mrkp/network.h"
#include "methods/onnd/network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace {

const std::string kDir = std::string(AFN_TEST_DATA) + "/baselines_parity/";

/// Max abs error relative to max(1, |want|) (ONND's outputs reach ~6).
double maxError(const afn::Image& got, const afn::nn::WeightTensor& want)
{
    EXPECT_EQ(got.height(), want.dims[0]);
    EXPECT_EQ(got.width(), want.dims[1]);
    EXPECT_EQ(got.channels(), want.dims[2]);
    if (static_cast<std::int64_t>(got.size()) != want.numel())
        return 1e30;
    double e = 0.0;
    for (std::size_t k = 0; k < got.size(); ++k)
        e = std::max(e,
            std::fabs(got.data()[k] - want.data[k])
                / std::max(1.0, std::fabs(double(want.data[k]))));
    return e;
}

struct FrameInputs {
    afn::Image cta, albedo, normal01, depth01;
    afn::nn::BaselineFeatureViews features() const
    {
        return { &cta, &albedo, &normal01, &depth01 };
    }
};

FrameInputs frameInputs(const afn::nn::WeightsArchive& c, int t)
{
    const std::string s = std::to_string(t);
    return { afntest::toImage(c.tensor("cta" + s)), afntest::toImage(c.tensor("albedo" + s)),
        afntest::toImage(c.tensor("normal01" + s)), afntest::toImage(c.tensor("depth01" + s)) };
}

constexpr double kTol = 4e-6;

/// Every tensor of the archive counted once (the PyTorch model's parameter count).
long archiveParameters(const afn::nn::WeightsArchive& a)
{
    long n = 0;
    for (const auto& [name, t] : a.tensors())
        n += static_cast<long>(t.numel());
    return n;
}

} // namespace

TEST(OnndMrkpParity, OnndMatchesPyTorchOverThreeFrames)
{
    const auto c = afntest::loadFile(kDir + "onnd_case.afnw");
    afn::onnd::Network net;
    const auto weights = afntest::loadFile(kDir + "onnd_weights.afnw");
    net.load(weights);
    EXPECT_EQ(net.levels(), 3);
    EXPECT_EQ(net.parameters(), archiveParameters(weights)); // every tensor is used
    afn::Image out;
    for (int t = 0; t < 3; ++t) {
        const FrameInputs f = frameInputs(c, t);
        net.run(f.features(), out);
        const double e = maxError(out, c.tensor("irr" + std::to_string(t)));
        std::printf("onnd frame %d: max error %.3g\n", t, e);
        EXPECT_LT(e, kTol) << "frame " << t;
    }
    // Without the state (reset) frame 2 differs from the recurrent run: the state matters.
    net.resetState();
    const FrameInputs f2 = frameInputs(c, 2);
    net.run(f2.features(), out);
    EXPECT_GT(maxError(out, c.tensor("irr2")), 1e-3);
}

TEST(OnndMrkpParity, MrkpMatchesPyTorch)
{
    const auto c = afntest::loadFile(kDir + "mrkp_case.afnw");
    afn::mrkp::Network net;
    const auto weights = afntest::loadFile(kDir + "mrkp_weights.afnw");
    net.load(weights);
    EXPECT_EQ(net.parameters(), archiveParameters(weights)); // every tensor is used
    const FrameInputs f = frameInputs(c, 0);
    afn::Image out, again;
    net.run(f.features(), out);
    const double e = maxError(out, c.tensor("irr0"));
    std::printf("mrkp: max error %.3g\n", e);
    EXPECT_LT(e, kTol);
    net.run(f.features(), again); // buffers reused: identical
    EXPECT_TRUE(std::equal(out.data(), out.data() + out.size(), again.data()));
}

TEST(OnndMrkpParity, WrongArchiveIsRejected)
{
    const auto onndWeights = afntest::loadFile(kDir + "onnd_weights.afnw");
    const auto mrkpWeights = afntest::loadFile(kDir + "mrkp_weights.afnw");
    afn::mrkp::Network m;
    EXPECT_THROW(m.load(onndWeights), afn::Exception);
    afn::onnd::Network o;
    EXPECT_THROW(o.load(mrkpWeights), afn::Exception);
    EXPECT_FALSE(m.loaded());
    EXPECT_FALSE(o.loaded());
}
