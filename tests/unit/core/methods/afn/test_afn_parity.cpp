// SPDX-License-Identifier: Apache-2.0
// PyTorch <-> C++ parity: the committed vectors of tests/data/afn_parity (regenerate with
// `cd training && /usr/bin/python3 -m afn.make_parity_vectors`) through the C++ engine.
// A 37x21 frame (padding rule covered), random-initialised narrow weights. The tolerance is float
// rounding: the two sides sum in different orders and use different exp/pow implementations.
#include "afn_test_util.h"
#include "base/exception.h"
#include "isa_scope.h"
#include "methods/afn/network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

struct Err {
    double maxAbs = 0, maxRel = 0;
};

/// `a` with metadata `key` set to `value`.
afn::nn::WeightsArchive withMeta(
    const afn::nn::WeightsArchive& a, const std::string& key, const std::string& value)
{
    auto meta = a.metadata();
    meta[key] = value;
    return afn::nn::WeightsArchive::fromTensors(a.tensors(), meta, a.source());
}

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
    afn::Image history;
    if (c.has("history01"))
        history = afntest::toImage(c.tensor("history01"));
    afn::afnet::Inputs in { &c1, &cta, &alb, &nrm, &dep, c.has("history01") ? &history : nullptr };
    EXPECT_EQ(net.hasHistoryInput(), c.has("history01"));
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
    EXPECT_EQ(net.hasAlbedoTrust(), c.has("t"));
    if (c.has("t"))
        EXPECT_LT(compare(net.albedoTrust(), c.tensor("t"), "t").maxAbs, tol);
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

TEST(AfnParity, HistoryInputModelMatchesPyTorch)
{
    // variant full with the 14th input channel history01 (model.py ``history``).
    checkVariant("history", afn::afnet::Variant::Full);
}

TEST(AfnParity, AlbedoTrustModelMatchesPyTorch)
{
    // variant full with the history input and the learned albedo trust (model.py
    // ``albedo_trust``, methods/afn/albedo_trust.h), its head random so t spreads over (0, 1).
    checkVariant("trust", afn::afnet::Variant::Full);
}

// Weights that declare the albedo trust wrongly are refused at load.
TEST(AfnParity, RejectsAnAlbedoTrustItCannotRun)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
    const auto weights = afntest::loadFile(dir + "weights_trust.afnw");
    afn::afnet::Network net;
    EXPECT_THROW(net.load(withMeta(weights, "albedoTrust", "2")), afn::Exception);
    EXPECT_THROW(net.load(withMeta(weights, "variant", "1spp")), afn::Exception);
    const auto plain = afntest::loadFile(dir + "weights_full.afnw");
    EXPECT_THROW(net.load(withMeta(plain, "albedoTrust", "1")), afn::Exception); // no headG
    net.load(weights);
    EXPECT_TRUE(net.hasAlbedoTrust());
}

// The history input is read: other history01 values give another output, and a model with the
// history input refuses inputs without history01 (a missing input, never a silent default).
TEST(AfnParity, HistoryInputIsReadAndRequired)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
    const auto c = afntest::loadFile(dir + "case_history.afnw");
    afn::afnet::Network net;
    net.load(afntest::loadFile(dir + "weights_history.afnw"));
    ASSERT_TRUE(net.hasHistoryInput());
    EXPECT_EQ(net.inputChannels(), 14);
    const afn::Image c1 = afntest::toImage(c.tensor("c1")), cta = afntest::toImage(c.tensor("cta"));
    const afn::Image alb = afntest::toImage(c.tensor("albedo"));
    const afn::Image nrm = afntest::toImage(c.tensor("normal01"));
    const afn::Image dep = afntest::toImage(c.tensor("depth01"));
    const afn::Image given = afntest::toImage(c.tensor("history01"));
    const afn::Image ones(given.width(), given.height(), 1, 1.0f);
    afn::Image a, b;
    net.run({ &c1, &cta, &alb, &nrm, &dep, &given }, a);
    net.run({ &c1, &cta, &alb, &nrm, &dep, &ones }, b);
    double maxDiff = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
        maxDiff = std::max(maxDiff, static_cast<double>(std::fabs(a.data()[k] - b.data()[k])));
    EXPECT_GT(maxDiff, 1e-3);
    EXPECT_THROW(net.run({ &c1, &cta, &alb, &nrm, &dep, nullptr }, a), afn::Exception);
    const auto weights = afntest::loadFile(dir + "weights_history.afnw");
    afn::afnet::Network bad;
    EXPECT_THROW(bad.load(withMeta(weights, "history", "2")), afn::Exception);
    EXPECT_THROW(bad.load(withMeta(weights, "history", "0")), afn::Exception); // 14-ch enc1
    EXPECT_THROW(bad.load(withMeta(weights, "variant", "ta")), afn::Exception);
}

TEST(AfnParity, QuarterScaleModelMatchesPyTorch)
{
    // variant full with the quarter-resolution scale (quarter_scale.h), beta ~ 0.5: run() takes
    // the whole-frame path, so the stripe comparison in checkVariant holds by construction and
    // the PyTorch comparison is what tests the scale.
    checkVariant("quarter", afn::afnet::Variant::Full);
}

// bf16 convolutions (cpu/conv_avx512_bf16.cpp) against the same PyTorch fp32 vectors: the
// stated tolerance of the reduced precision. Operands rounded to 8 significant bits move each
// layer's sums by about 2^-9 relatively; through the kernels' softmax and the fusion the output
// (O(1) here) moved by 6.1e-4 (full) and 8.4e-4 (quarter) at most, alpha by 8.8e-4, where fp32
// holds 4e-6. Tolerance 3e-3.
TEST(AfnParity, Bf16WithinItsToleranceOfPyTorch)
{
    if (!isa_test::haveAvx512())
        GTEST_SKIP() << "the bf16 engine is part of the AVX-512 kernels";
    const isa_test::IsaScope isa(afn::cpu::Isa::Avx512);
    for (const char* variant : { "full", "quarter" }) {
        const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
        const auto c = afntest::loadFile(dir + "case_" + variant + ".afnw");
        afn::afnet::Network net;
        net.load(afntest::loadFile(dir + "weights_" + variant + ".afnw"));
        net.setPrecision(afn::nn::Precision::Bf16);
        ASSERT_EQ(net.precision(), afn::nn::Precision::Bf16);
        const afn::Image c1 = afntest::toImage(c.tensor("c1"));
        const afn::Image cta = afntest::toImage(c.tensor("cta"));
        const afn::Image alb = afntest::toImage(c.tensor("albedo"));
        const afn::Image nrm = afntest::toImage(c.tensor("normal01"));
        const afn::Image dep = afntest::toImage(c.tensor("depth01"));
        const afn::afnet::Inputs in { &c1, &cta, &alb, &nrm, &dep };
        afn::Image o, striped;
        net.runWholeFrame(in, o);
        net.run(in, striped);
        EXPECT_TRUE(std::equal(o.data(), o.data() + o.size(), striped.data()))
            << "bf16: the stripe path differs from the whole-frame path";
        std::printf("bf16 parity %s:\n", variant);
        const Err alpha = compare(net.alpha(), c.tensor("alpha"), "alpha");
        const Err out = compare(o, c.tensor("o"), "o");
        EXPECT_LT(alpha.maxAbs, 3e-3);
        EXPECT_LT(out.maxAbs, 3e-3);
        EXPECT_GT(out.maxAbs, 4e-6) << "no bf16 rounding in the output: the layers ran in fp32";
    }
}

TEST(AfnParity, QuarterScaleChangesTheResult)
{
    // The same weights without head4 (quarter=0) give another fused image: the scale is applied.
    const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
    const auto c = afntest::loadFile(dir + "case_quarter.afnw");
    const afn::Image c1 = afntest::toImage(c.tensor("c1")), cta = afntest::toImage(c.tensor("cta"));
    const afn::Image alb = afntest::toImage(c.tensor("albedo"));
    const afn::Image nrm = afntest::toImage(c.tensor("normal01"));
    const afn::Image dep = afntest::toImage(c.tensor("depth01"));
    const afn::afnet::Inputs in { &c1, &cta, &alb, &nrm, &dep };
    afn::afnet::Network with, without;
    const auto weights = afntest::loadFile(dir + "weights_quarter.afnw");
    with.load(weights);
    EXPECT_TRUE(with.hasQuarterScale());
    without.load(withMeta(weights, "quarter", "0"));
    EXPECT_FALSE(without.hasQuarterScale());
    afn::Image a, b;
    with.run(in, a);
    without.run(in, b);
    double maxDiff = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
        maxDiff = std::max(maxDiff, static_cast<double>(std::fabs(a.data()[k] - b.data()[k])));
    EXPECT_GT(maxDiff, 1e-2);
}

TEST(AfnParity, RejectsAQuarterScaleItCannotRun)
{
    const std::string dir = std::string(AFN_TEST_DATA) + "/afn_parity/";
    auto expectError = [](const afn::nn::WeightsArchive& a, const std::string& what) {
        afn::afnet::Network net;
        try {
            net.load(a);
            FAIL() << "expected an exception for " << what;
        } catch (const afn::Exception& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
        EXPECT_FALSE(net.loaded());
    };
    const auto fusion = afntest::loadFile(dir + "weights_fusion.afnw"); // no head4 tensor
    expectError(withMeta(fusion, "quarter", "1"), "missing tensor 'head4.weight'");
    const auto quarter = afntest::loadFile(dir + "weights_quarter.afnw");
    expectError(withMeta(quarter, "quarter", "yes"), "quarter='yes' (0 or 1)");
    expectError(
        withMeta(quarter, "variant", "ta"), "the quarter scale needs variant full or fusion");
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
