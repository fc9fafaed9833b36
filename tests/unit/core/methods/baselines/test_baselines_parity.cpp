// SPDX-License-Identifier: Apache-2.0
// PyTorch <-> C++ parity of the learned baselines WSKPN and NBGD: the committed vectors of
// tests/data/baselines_parity (regenerate with `cd training && /usr/bin/python3 -m
// afn.baselines.make_parity_vectors`) through the C++ networks, on both kernel families. A 37x21
// frame, random weights. The tolerance is float rounding: the sides sum in different orders and
// use different exp/pow implementations.
#include "afn_test_util.h"
#include "base/exception.h"
#include "cpu/isa.h"
#include "methods/nbgd/network.h"
#include "methods/wskpn/network.h"
#include "nn/baseline_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

/// Max abs error relative to max(|want|, 1) per value (the outputs are O(1)).
double maxError(const afn::Image& got, const afn::nn::WeightTensor& want, const char* what)
{
    EXPECT_EQ(got.height(), want.dims[0]) << what;
    EXPECT_EQ(got.width(), want.dims[1]) << what;
    EXPECT_EQ(got.channels(), want.dims[2]) << what;
    if (static_cast<std::int64_t>(got.size()) != want.numel())
        return 1e30;
    double e = 0;
    for (std::size_t k = 0; k < got.size(); ++k)
        e = std::max(e,
            std::fabs(got.data()[k] - want.data[k])
                / std::max(1.0, std::fabs(double(want.data[k]))));
    std::printf("  %-6s max error %.3g\n", what, e);
    return e;
}

struct Case {
    afn::nn::WeightsArchive weights, data;
    afn::Image cta, input;
};

Case loadCase(const std::string& method)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/baselines_parity/";
    Case c { afntest::loadFile(dir + method + "_weights.afnw"),
        afntest::loadFile(dir + method + "_case.afnw"), {}, {} };
    c.cta = afntest::toImage(c.data.tensor("cta"));
    afn::nn::BaselineFeatures f;
    f.albedo = afntest::toImage(c.data.tensor("albedo"));
    f.normal01 = afntest::toImage(c.data.tensor("normal01"));
    f.depth01 = afntest::toImage(c.data.tensor("depth01"));
    afn::nn::baselineInput(c.cta, f, c.input);
    return c;
}

/// Runs `net` with the case's weights on its input and returns the output; prints the heading of
/// the error lines that follow.
template <class Network> afn::Image runCase(Network& net, const Case& c, const char* method)
{
    net.load(c.weights);
    afn::Image o;
    net.run(c.input, c.cta, o);
    std::printf("%s parity (%s):\n", method, afn::cpu::isaName(afn::cpu::activeIsa()));
    return o;
}

class BaselinesParity : public ::testing::TestWithParam<afn::cpu::Isa> {
protected:
    void SetUp() override
    {
        m_before = afn::cpu::activeIsa();
        afn::cpu::forceIsa(GetParam());
    }
    void TearDown() override { afn::cpu::forceIsa(m_before); }
    afn::cpu::Isa m_before = afn::cpu::Isa::Portable;
};

// Measured: head logits (up to ~10) 8.5e-6, every other output <= 1.3e-6 of PyTorch on both kernel
// families; 2e-5 catches any graph difference (a wrong
// tap, window, grid cell or blend changes values by > 1e-2).
constexpr double kTol = 2e-5;

} // namespace

TEST_P(BaselinesParity, WskpnMatchesPyTorch)
{
    const Case c = loadCase("wskpn");
    afn::wskpn::Network net;
    const afn::Image o = runCase(net, c, "wskpn");
    EXPECT_LT(maxError(net.head(), c.data.tensor("head"), "head"), kTol);
    EXPECT_LT(maxError(o, c.data.tensor("o"), "o"), kTol);
    // The folding at export is exact: the training model with its branches gives the same output.
    EXPECT_LT(maxError(o, c.data.tensor("o_branches"), "o(br.)"), kTol);
}

TEST_P(BaselinesParity, NbgdMatchesPyTorch)
{
    const Case c = loadCase("nbgd");
    afn::nbgd::Network net;
    const afn::Image o = runCase(net, c, "nbgd");
    EXPECT_LT(maxError(net.guides(), c.data.tensor("guides"), "guides"), kTol);
    EXPECT_LT(maxError(net.sliced(0), c.data.tensor("g1"), "g1"), kTol);
    EXPECT_LT(maxError(net.sliced(1), c.data.tensor("g2"), "g2"), kTol);
    EXPECT_LT(maxError(net.sliced(2), c.data.tensor("g3"), "g3"), kTol);
    EXPECT_LT(maxError(o, c.data.tensor("o"), "o"), kTol);
}

TEST(BaselinesWeights, WrongArchivesAreRejected)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/baselines_parity/";
    const auto wskpnWeights = afntest::loadFile(dir + "wskpn_weights.afnw");
    const auto nbgdWeights = afntest::loadFile(dir + "nbgd_weights.afnw");
    afn::wskpn::Network w;
    afn::nbgd::Network n;
    EXPECT_THROW(w.load(nbgdWeights), afn::Exception);
    EXPECT_THROW(n.load(wskpnWeights), afn::Exception);
    EXPECT_FALSE(w.loaded());
    EXPECT_FALSE(n.loaded());
}

INSTANTIATE_TEST_SUITE_P(Isa, BaselinesParity,
    ::testing::Values(afn::cpu::Isa::Portable, afn::cpu::Isa::Avx512),
    [](const auto& info) { return std::string(afn::cpu::isaName(info.param)); });
