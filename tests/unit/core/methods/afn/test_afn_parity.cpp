// SPDX-License-Identifier: Apache-2.0
// PyTorch <-> C++ parity: the committed vectors of tests/data/afn_parity (regenerate with
// `cd training && /usr/bin/python3 -m afn.make_parity_vectors`) through the C++ engine.
// A 37x21 frame (padding rule covered), random-initialised narrow weights. The tolerance is float
// rounding: the two sides sum in different orders and use different exp/pow implementations.
#include "afn_test_util.h"
#include "base/exception.h"
#include "methods/afn/network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

struct Err {
    double maxAbs = 0, maxRel = 0;
};

Err compare(const afn::Image& got, const afn::nn::WeightTensor& want, const char* what)
{
    Err e;
    EXPECT_EQ(got.height(), want.dims[0]) << what;
    EXPECT_EQ(got.width(), want.dims[1]) << what;
    EXPECT_EQ(got.channels(), want.dims[2]) << what;
    if (static_cast<std::int64_t>(got.size()) != want.numel())
        return e;
    for (std::size_t k = 0; k < got.size(); ++k) {
        const double g = got.data()[k], w = want.data[k], d = std::fabs(g - w);
        e.maxAbs = std::max(e.maxAbs, d);
        e.maxRel = std::max(e.maxRel, d / std::max(std::fabs(w), 1e-3));
    }
    std::printf("  %-7s max abs error %.3g, max rel error %.3g\n", what, e.maxAbs, e.maxRel);
    return e;
}

void checkVariant(const std::string& variant, afn::afnet::Variant expect)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
    const auto weights = afntest::loadFile(dir + "weights_" + variant + ".afnw");
    const auto c = afntest::loadFile(dir + "case_" + variant + ".afnw");
    afn::afnet::Network net;
    net.load(weights);
    EXPECT_EQ(net.variant(), expect);
    const afn::Image c1 = afntest::toImage(c.tensor("c1")), cta = afntest::toImage(c.tensor("cta"));
    const afn::Image alb = afntest::toImage(c.tensor("albedo"));
    const afn::Image nrm = afntest::toImage(c.tensor("normal01"));
    const afn::Image dep = afntest::toImage(c.tensor("depth01"));
    afn::afnet::Inputs in { &c1, &cta, &alb, &nrm, &dep };
    afn::Image o, striped;
    net.runWholeFrame(in, o); // keeps the intermediates
    net.run(in, striped);
    EXPECT_TRUE(std::equal(o.data(), o.data() + o.size(), striped.data()))
        << "the stripe path differs from the whole-frame path";
    std::printf("parity %s (%dx%d):\n", variant.c_str(), o.width(), o.height());
    // Outputs are O(1) here (max ~1.2); measured max abs error 3.6e-7 (about 3 ulps of 1.0).
    // 4e-6 leaves room for other compilers/libm while still catching any real graph difference.
    constexpr double tol = 4e-6;
    EXPECT_LT(compare(net.filtered1Half(), c.tensor("d_1spp"), "d_1spp").maxAbs, tol);
    EXPECT_LT(compare(net.alpha(), c.tensor("alpha"), "alpha").maxAbs, tol);
    EXPECT_LT(compare(net.filteredTa(), c.tensor("d_ta"), "d_ta").maxAbs, tol);
    EXPECT_LT(compare(net.fused(), c.tensor("i"), "i").maxAbs, tol);
    EXPECT_LT(compare(o, c.tensor("o"), "o").maxAbs, tol);
    // The same engine run twice (buffers reused) gives identical results.
    afn::Image o2;
    net.run(in, o2);
    EXPECT_TRUE(std::equal(striped.data(), striped.data() + striped.size(), o2.data()));
}

} // namespace

TEST(AfnParity, FullModelMatchesPyTorch)
{
    checkVariant("full", afn::afnet::Variant::Full);
}

TEST(AfnParity, FusionModelMatchesPyTorch)
{
    checkVariant("fusion", afn::afnet::Variant::Fusion);
}

TEST(AfnParity, RejectsWeightsOfAnotherShape)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
    const auto c = afntest::loadFile(dir + "case_full.afnw"); // has no enc1.weight
    afn::afnet::Network net;
    try {
        net.load(c);
        FAIL() << "expected an exception";
    } catch (const afn::Exception& e) {
        EXPECT_NE(std::string(e.what()).find("missing tensor 'enc1.weight'"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(net.loaded());
}
