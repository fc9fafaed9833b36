// SPDX-License-Identifier: Apache-2.0
// Input-aware afn: input-set spelling, the model choice and its fallback order, the
// missing-model error, the reported path, and the network inputs of a model that uses fewer
// inputs than the frame has.
#include "base/exception.h"
#include "filter/frame.h"
#include "methods/afn/input_set.h"
#include "methods/afn/model_set.h"
#include "methods/afn/network_inputs.h"
#include "methods/afn/random_weights.h"
#include "stages/demodulate.h"

#include <gtest/gtest.h>

#include <limits>

#include <string>
#include <utility>
#include <vector>

using afn::afnet::InputSet;

namespace {

/// All 16 input sets.
std::vector<InputSet> allSets()
{
    std::vector<InputSet> out;
    for (int m = 0; m < 16; ++m)
        out.push_back({ (m & 1) != 0, (m & 2) != 0, (m & 4) != 0, (m & 8) != 0 });
    return out;
}

/// A random-weights archive trained "for" `inputs` ("" = no inputs key) at `spp` ("" = no key).
afn::nn::WeightsArchive archiveFor(
    const std::string& inputs, unsigned seed, const std::string& spp = "")
{
    afn::afnet::Architecture narrow;
    narrow.enc = { 4, 4, 4 };
    narrow.dec = { 4, 4 };
    narrow.refine = 4;
    const afn::nn::WeightsArchive a = afn::afnet::randomWeights(narrow, seed);
    std::map<std::string, std::string> meta = { { "variant", "full" }, { "format", "afn" } };
    if (!inputs.empty())
        meta["inputs"] = inputs;
    if (!spp.empty())
        meta["spp"] = spp;
    return afn::nn::WeightsArchive::fromTensors(a.tensors(), meta, "test " + inputs);
}

} // namespace

TEST(AfnInputSet, SpellingsRoundTrip)
{
    for (const InputSet& s : allSets()) {
        InputSet back;
        ASSERT_TRUE(afn::afnet::parseInputSet(afn::afnet::inputSetKey(s), back));
        EXPECT_EQ(back, s) << afn::afnet::inputSetKey(s);
        const std::string name = afn::afnet::inputSetName(s);
        EXPECT_EQ(name.rfind("color", 0), 0u) << name;
        ASSERT_TRUE(afn::afnet::parseInputSet(name, back));
        EXPECT_EQ(back, s) << name;
    }
    InputSet s;
    EXPECT_TRUE(afn::afnet::parseInputSet("normal, albedo", s));
    EXPECT_EQ(afn::afnet::inputSetKey(s), "albedo,normal");
    EXPECT_FALSE(afn::afnet::parseInputSet("albedo,motion", s)); // "temporal", not "motion"
    EXPECT_EQ(afn::afnet::inputSetKey(s), "albedo,normal") << "unchanged on failure";
}

TEST(AfnInputSet, ChoosesTheLargestCoveredModel)
{
    afn::afnet::ModelSet models;
    models.add(archiveFor("", 1)); // no key: the full set
    models.add(archiveFor("color", 2));
    models.add(archiveFor("albedo,normal", 3));
    EXPECT_EQ(models.listing(), "color+albedo+normal+depth+temporal; color; color+albedo+normal");
    for (const InputSet& available : allSets()) {
        // Expected by the documented order, written out independently of choose().
        std::string expected = "color";
        if (available.albedo && available.normal)
            expected = "color+albedo+normal";
        // The full model also covers a frame without a history (it runs single-frame).
        if (available.albedo && available.normal && available.depth)
            expected = "color+albedo+normal+depth+temporal";
        const afn::afnet::Model* m = models.choose(available);
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(afn::afnet::inputSetName(m->inputs), expected)
            << "available " << afn::afnet::inputSetName(available);
    }
}

TEST(AfnInputSet, ChoosesTheModelTrainedNearestTheSampleCount)
{
    afn::afnet::ModelSet models;
    models.add(archiveFor("", 1)); // no spp key: 1 spp
    models.add(archiveFor("", 2, "64"));
    models.add(archiveFor("", 3, "16"));
    models.add(archiveFor("color", 4));
    EXPECT_EQ(models.listing(),
        "color+albedo+normal+depth+temporal; color+albedo+normal+depth+temporal (64 spp); "
        "color+albedo+normal+depth+temporal (16 spp); color");
    // Nearest in log2, ties to the lower count, unknown (0) as 1; written out by hand.
    const std::vector<std::pair<int, int>> expected = { { 0, 1 }, { 1, 1 }, { 2, 1 }, { 3, 1 },
        { 4, 1 }, { 5, 16 }, { 16, 16 }, { 32, 16 }, { 33, 64 }, { 64, 64 }, { 100000, 64 } };
    for (const auto& [spp, want] : expected) {
        const afn::afnet::Model* m = models.choose(InputSet::full(), spp);
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(m->spp, want) << "frame at " << spp << " spp";
        EXPECT_EQ(m->inputs, InputSet::full());
    }
    // The input set comes first: a colour-only frame at 64 spp gets the (1-spp) colour model.
    const afn::afnet::Model* colour = models.choose(InputSet {}, 64);
    ASSERT_NE(colour, nullptr);
    EXPECT_EQ(colour->spp, 1);
    EXPECT_EQ(afn::afnet::describeChoice(InputSet::full(), *models.choose(InputSet::full(), 16)),
        "model color+albedo+normal+depth+temporal (16 spp), temporal");
    EXPECT_EQ(afn::afnet::describeChoice(InputSet::full(), *models.choose(InputSet::full(), 1)),
        "model color+albedo+normal+depth+temporal, temporal");
}

TEST(AfnInputSet, AFrameWithoutHistoryRunsATemporalModelSingleFrame)
{
    afn::afnet::ModelSet models;
    models.add(archiveFor("", 1)); // the full set, 1 spp
    models.add(archiveFor("", 2, "16"));
    models.add(archiveFor("albedo,normal", 3));
    models.add(archiveFor("color", 4));
    const InputSet still { true, true, true, false }; // no motion, no positions with a camera
    // Written out by hand: the temporal models use albedo, normal and depth (3) against the
    // single-frame model's 2; then the sample count.
    for (const auto& [spp, want] : std::vector<std::pair<int, int>> { { 1, 1 }, { 16, 16 } }) {
        const afn::afnet::Model* m = models.choose(still, spp);
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(m->inputs, InputSet::full()) << spp;
        EXPECT_EQ(m->spp, want);
        EXPECT_EQ(afn::afnet::inputsToUse(still, *m), still)
            << "the temporal branch reads the frame";
    }
    EXPECT_EQ(afn::afnet::describeChoice(still, *models.choose(still, 16)),
        "model color+albedo+normal+depth+temporal (16 spp), single-frame (no motion or position: "
        "the temporal branch reads this frame)");
    // Without depth the temporal models are not covered: the single-frame model as before.
    const afn::afnet::Model* noDepth = models.choose({ true, true, false, false }, 16);
    ASSERT_NE(noDepth, nullptr);
    EXPECT_EQ(noDepth->inputs, (InputSet { true, true, false, false }));
    // With a history the temporal branch runs on it.
    EXPECT_EQ(afn::afnet::inputsToUse(InputSet::full(), *models.choose(InputSet::full(), 16)),
        InputSet::full());
}

TEST(AfnInputSet, OnATieASingleFrameModelComesBeforeATemporalOneRunSingleFrame)
{
    afn::afnet::ModelSet models;
    models.add(archiveFor("", 1));
    models.add(archiveFor("albedo,normal,depth", 2));
    const InputSet still { true, true, true, false };
    const afn::afnet::Model* m = models.choose(still);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->inputs, still);
    // A temporal model that would read nothing but the colour does not beat one that reads albedo.
    afn::afnet::ModelSet two;
    two.add(archiveFor("temporal", 3));
    two.add(archiveFor("albedo", 4));
    const afn::afnet::Model* a = two.choose({ true, false, false, false });
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->inputs, (InputSet { true, false, false, false }));
}

TEST(AfnInputSet, InvalidSampleCountMetadataIsRefused)
{
    afn::afnet::ModelSet models;
    for (const char* bad : { "0", "-4", "16x", "abc", "2000000" })
        EXPECT_THROW(models.add(archiveFor("", 1, bad)), afn::Exception) << bad;
    EXPECT_TRUE(models.empty());
}

TEST(AfnInputSet, TiesPreferTheTemporalModel)
{
    afn::afnet::ModelSet models;
    models.add(archiveFor("albedo", 1));
    models.add(archiveFor("temporal", 2));
    const afn::afnet::Model* m = models.choose({ true, false, false, true });
    ASSERT_NE(m, nullptr);
    EXPECT_TRUE(m->inputs.temporal);
    EXPECT_FALSE(m->inputs.albedo);
}

TEST(AfnInputSet, NoCoveredModelIsAnErrorNamingBoth)
{
    afn::afnet::ModelSet models;
    models.add(archiveFor("", 1));
    const InputSet colourOnly;
    EXPECT_EQ(models.choose(colourOnly), nullptr);
    try {
        models.throwNoModelFor(colourOnly);
        FAIL() << "must throw";
    } catch (const afn::Exception& e) {
        const std::string text = e.what();
        EXPECT_NE(text.find("no weights for the inputs color "), std::string::npos) << text;
        EXPECT_NE(text.find("color+albedo+normal+depth+temporal"), std::string::npos) << text;
    }
    EXPECT_EQ(afn::afnet::ModelSet().listing(), "none");
    EXPECT_THROW(models.add(archiveFor("albedo,motion", 4)), afn::Exception);
}

TEST(AfnInputSet, PathTextSaysModeAndUnusedInputs)
{
    using afn::afnet::describePath;
    EXPECT_EQ(describePath({}, {}),
        "model color, single-frame (no temporal branch: no motion or position)");
    EXPECT_EQ(describePath({ true, true, true, false }, { true, true, false, false }),
        "model color+albedo+normal, single-frame (no temporal branch: no motion or position); "
        "not used: depth");
    EXPECT_EQ(describePath({ false, false, false, true }, {}),
        "model color, single-frame (no temporal branch: the model has none); not used: temporal");
    EXPECT_EQ(describePath(InputSet::full(), InputSet::full()),
        "model color+albedo+normal+depth+temporal, temporal");
}

TEST(AfnInputSet, FrameInputsDecideTheSet)
{
    afn::Frame f;
    f.width = 4;
    f.height = 2;
    f.color = afn::Image(4, 2, 3, 1.0f);
    EXPECT_EQ(afn::afnet::inputSetOf(f), InputSet {});
    f.position = afn::Image(4, 2, 3);
    EXPECT_FALSE(afn::afnet::inputSetOf(f).temporal) << "positions need a camera";
    f.camera.valid = true;
    EXPECT_TRUE(afn::afnet::inputSetOf(f).temporal);
    f.position = afn::Image();
    f.motion = afn::Image(4, 2, 2);
    f.depth = afn::Image(4, 2, 1);
    EXPECT_EQ(afn::afnet::inputSetOf(f), (InputSet { false, false, true, true }));
}

TEST(AfnInputSet, UnusedInputsAreHeldNeutral)
{
    const int w = 5, h = 3;
    afn::Frame f;
    f.width = w;
    f.height = h;
    f.color = afn::Image(w, h, 3);
    f.albedo = afn::Image(w, h, 3);
    f.normal = afn::Image(w, h, 3);
    f.depth = afn::Image(w, h, 1);
    for (std::size_t k = 0; k < f.color.size(); ++k) {
        f.color.data()[k] = 0.1f * float(k % 7);
        f.albedo.data()[k] = 0.25f + 0.05f * float(k % 5);
        f.normal.data()[k] = (k % 3) == 2 ? 1.0f : 0.0f;
    }
    for (std::size_t k = 0; k < f.depth.size(); ++k)
        f.depth.data()[k] = 1.0f + float(k);
    afn::Image irradiance, accumulated(w, h, 3, 9.0f), length(w, h, 1, 4.0f);
    length.data()[1] = 1.0f; // reset there
    length.data()[2] = 1000.0f; // beyond BMFR's cap
    length.data()[3] = std::numeric_limits<float>::quiet_NaN();
    afn::demodulate(f, irradiance);

    afn::afnet::NetworkInputs colourOnly;
    colourOnly.prepare(f, {}, irradiance, accumulated, &length);
    for (std::size_t k = 0; k < f.color.size(); ++k) {
        EXPECT_NEAR(colourOnly.color1().data()[k], f.color.data()[k], 1e-6f) << k;
        EXPECT_EQ(colourOnly.colorTa().data()[k], colourOnly.color1().data()[k]) << "single-frame";
        EXPECT_EQ(colourOnly.albedo().data()[k], 1.0f);
        EXPECT_EQ(colourOnly.normal01().data()[k], 0.5f);
    }
    for (std::size_t k = 0; k < f.depth.size(); ++k) {
        EXPECT_EQ(colourOnly.depth01().data()[k], 0.0f);
        EXPECT_EQ(colourOnly.history01().data()[k], 1.0f) << "single-frame: no history";
    }
    afn::Image result(w, h, 3, -2.0f), out;
    result.data()[4] = 3.0f;
    colourOnly.radiance(f, result, out);
    EXPECT_EQ(out.data()[0], 0.0f);
    EXPECT_EQ(out.data()[4], 3.0f) << "not remodulated: the model filtered the colour itself";

    afn::afnet::NetworkInputs withAux;
    withAux.prepare(f, { true, true, false, false }, irradiance, accumulated, nullptr);
    EXPECT_TRUE(withAux.history01().empty()) << "not asked for: no memory";
    EXPECT_EQ(withAux.color1().data()[4], irradiance.data()[4]);
    EXPECT_EQ(withAux.colorTa().data()[4], irradiance.data()[4]);
    EXPECT_EQ(withAux.albedo().data()[4], f.albedo.data()[4]);
    EXPECT_EQ(withAux.normal01().data()[2], 1.0f);
    EXPECT_EQ(withAux.depth01().data()[1], 0.0f) << "depth present but not used";

    afn::afnet::NetworkInputs temporal;
    temporal.prepare(f, InputSet::full(), irradiance, accumulated, &length);
    EXPECT_EQ(temporal.colorTa().data()[4], 9.0f);
    EXPECT_GT(temporal.depth01().data()[1], 0.0f);
    // history01 = 1 / the history length, in [1/255, 1]; NaN counts as no history.
    EXPECT_EQ(temporal.history01().data()[0], 0.25f);
    EXPECT_EQ(temporal.history01().data()[1], 1.0f);
    EXPECT_EQ(temporal.history01().data()[2], 1.0f / 255.0f);
    EXPECT_EQ(temporal.history01().data()[3], 1.0f);
}
