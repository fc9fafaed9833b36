// SPDX-License-Identifier: Apache-2.0
// AFN large (methods/afn/network_large.h): PyTorch <-> C++ parity on the committed vectors
// (tests/data/afn_parity/*_large.afnw, `cd training && /usr/bin/python3 -m
// afn.make_parity_vectors`), the TA input unused, the stage calls refused, the choice by sample
// count among the full-input-set models, and the afn filter running it on a small sequence.
#include "afn_test_util.h"
#include "base/exception.h"
#include "filter/registry.h"
#include "methods/afn/model_set.h"
#include "methods/afn/network.h"
#include "methods/afn/random_weights.h"
#include "still_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

const std::string kDir = std::string(AFN_TEST_DATA) + "/afn_parity/";

double maxAbsError(const afn::Image& got, const afn::nn::WeightTensor& want, const char* what)
{
    EXPECT_EQ(got.height(), want.dims[0]) << what;
    EXPECT_EQ(got.width(), want.dims[1]) << what;
    EXPECT_EQ(got.channels(), want.dims[2]) << what;
    if (static_cast<std::int64_t>(got.size()) != want.numel())
        return 1e30;
    double e = 0.0;
    for (std::size_t k = 0; k < got.size(); ++k)
        e = std::max(e, std::fabs(double(got.data()[k]) - want.data[k]));
    std::printf("  %-7s max abs error %.3g\n", what, e);
    return e;
}

struct Case {
    afn::nn::WeightsArchive data = afntest::loadFile(kDir + "case_large.afnw");
    afn::Image c1 = afntest::toImage(data.tensor("c1"));
    afn::Image cta = afntest::toImage(data.tensor("cta"));
    afn::Image albedo = afntest::toImage(data.tensor("albedo"));
    afn::Image normal = afntest::toImage(data.tensor("normal01"));
    afn::Image depth = afntest::toImage(data.tensor("depth01"));
    afn::afnet::Inputs inputs() const { return { &c1, &cta, &albedo, &normal, &depth }; }
};

} // namespace

TEST(AfnLarge, MatchesPyTorch)
{
    afn::afnet::Network net;
    net.load(afntest::loadFile(kDir + "weights_large.afnw"));
    EXPECT_EQ(net.variant(), afn::afnet::Variant::Large);
    const Case c;
    afn::Image whole, striped;
    net.runWholeFrame(c.inputs(), whole);
    const afn::afnet::LargeNetwork& g = net.large();
    // alpha1 = sigmoid(channel 25 of head1), as PyTorch's torch.sigmoid.
    afn::Image alpha1(g.fullHead().width(), g.fullHead().height(), 1);
    for (int y = 0; y < alpha1.height(); ++y)
        for (int x = 0; x < alpha1.width(); ++x)
            alpha1.at(x, y)[0] = 1.0f / (1.0f + std::exp(-g.fullHead().at(x, y)[25]));
    std::printf("parity large (%dx%d):\n", whole.width(), whole.height());
    // The tolerance of the AFN parity test (test_afn_parity.cpp): float rounding only.
    constexpr double tol = 4e-6;
    EXPECT_LT(maxAbsError(g.filteredQuarter(), c.data.tensor("f3"), "f3"), tol);
    EXPECT_LT(maxAbsError(g.fusedHalf(), c.data.tensor("o2"), "o2"), tol);
    EXPECT_LT(maxAbsError(g.filteredFull(), c.data.tensor("f1"), "f1"), tol);
    EXPECT_LT(maxAbsError(alpha1, c.data.tensor("alpha1"), "alpha1"), tol);
    EXPECT_LT(maxAbsError(g.fused(), c.data.tensor("i"), "i"), tol);
    EXPECT_LT(maxAbsError(whole, c.data.tensor("o"), "o"), tol);
    // run() (the filter's path) is the same whole-frame graph; a second run reuses the buffers.
    net.run(c.inputs(), striped);
    EXPECT_TRUE(std::equal(whole.data(), whole.data() + whole.size(), striped.data()));
    EXPECT_EQ(net.skippedRows(), 0);
    EXPECT_GT(net.stageFlop(afn::afnet::Network::Stage::Refinement), 0.0);
}

TEST(AfnLarge, ReadsNoTemporalAccumulation)
{
    afn::afnet::Network net;
    net.load(afntest::loadFile(kDir + "weights_large.afnw"));
    const Case c;
    afn::Image a, b;
    net.run(c.inputs(), a);
    afn::afnet::Inputs noTa = c.inputs();
    noTa.colorTa = nullptr;
    net.run(noTa, b);
    EXPECT_TRUE(std::equal(a.data(), a.data() + a.size(), b.data()));
    EXPECT_THROW(net.prepare(c.inputs()), afn::Exception); // no stage-by-stage path
}

TEST(AfnLarge, RejectsAnAfnArchiveLabelledLarge)
{
    const afn::nn::WeightsArchive afnWeights = afntest::loadFile(kDir + "weights_full.afnw");
    const afn::nn::WeightsArchive relabelled = afn::nn::WeightsArchive::fromTensors(
        afnWeights.tensors(), { { "variant", "large" } }, "relabelled");
    afn::afnet::Network net;
    try {
        net.load(relabelled);
        FAIL() << "expected an exception";
    } catch (const afn::Exception& e) {
        EXPECT_NE(std::string(e.what()).find("invalid or corrupted weights"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(net.loaded());
}

TEST(AfnLarge, ChosenForFramesNearItsSampleCount)
{
    afn::afnet::ModelSet models;
    afn::afnet::Architecture narrow;
    narrow.enc = { 4, 4, 4 };
    narrow.dec = { 4, 4 };
    narrow.refine = 4;
    models.add(afn::afnet::randomWeights(narrow, 1)); // AFN, full input set, 1 spp
    const afn::nn::WeightsArchive large = afntest::loadFile(kDir + "weights_large.afnw");
    models.add(afn::nn::WeightsArchive::fromTensors(large.tensors(),
        { { "variant", "large" }, { "inputs", "albedo,normal,depth,temporal" }, { "spp", "64" } },
        "large at 64 spp"));
    const afn::afnet::InputSet all = afn::afnet::InputSet::full();
    for (const auto& [spp, variant] : std::vector<std::pair<int, afn::afnet::Variant>> {
             { 0, afn::afnet::Variant::Full }, { 1, afn::afnet::Variant::Full },
             { 4, afn::afnet::Variant::Full }, { 16, afn::afnet::Variant::Large },
             { 64, afn::afnet::Variant::Large }, { 512, afn::afnet::Variant::Large } }) {
        const afn::afnet::Model* m = models.choose(all, spp);
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(m->net.variant(), variant) << "frame at " << spp << " spp";
    }
    EXPECT_EQ(afn::afnet::describeChoice(all, *models.choose(all, 64)),
        "model color+albedo+normal+depth+temporal (64 spp, AFN large), temporal");
    // Without AFN large (the CUDA filter: no graph for it) the nearest other model, at any count.
    for (const int spp : { 0, 16, 64, 512 }) {
        const afn::afnet::Model* m = models.choose(all, spp, false);
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(m->net.variant(), afn::afnet::Variant::Full) << "frame at " << spp << " spp";
        EXPECT_EQ(m->spp, 1);
    }
    EXPECT_EQ(models.listing(),
        "color+albedo+normal+depth+temporal; color+albedo+normal+depth+temporal (64 spp, AFN "
        "large)");
}

TEST(AfnLarge, FilterDenoisesWithLargeWeights)
{
    auto f = afn::createFilter("afn");
    const int w = 19, h = 11;
    afntest::StillFrame still(w, h);
    still.bindTo(*f);
    still.bindMotionTo(*f); // the archive declares the full input set (no inputs key)
    const auto bytes = afntest::readBytes(kDir + "weights_large.afnw");
    f->setData("weights", bytes.data(), bytes.size());
    f->commit();
    for (int frame = 0; frame < 2; ++frame) {
        f->execute();
        for (std::size_t k = 0; k < still.out.size(); ++k) {
            ASSERT_TRUE(std::isfinite(still.out.data()[k]));
            ASSERT_GE(still.out.data()[k], 0.0f);
        }
    }
}
