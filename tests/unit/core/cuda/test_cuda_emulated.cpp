// SPDX-License-Identifier: Apache-2.0
// The CUDA engine's network and whole filter, run on the CPU through the host emulation
// (emulated_pipeline.h), against the CPU engine: the network input to half precision, and the
// whole filter within the documented tolerance (afn_output_compare.h) on synthetic sequences of
// several sizes, input sets and weights (the stages: test_cuda_emulated_stages.cpp). Built in
// every configuration: a GPU is not needed.
#include "afn_output_compare.h"
#include "afn_parity_cases.h"
#include "cuda/frame_constants.h"
#include "emulated_pipeline.h"
#include "emulated_test_util.h"
#include "filter/registry.h"
#include "methods/afn/model_set.h"
#include "methods/afn/network_inputs.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"
#include "methods/afn/work_rows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

using namespace afntest;

// The network input (with history01 where the weights read it), the decoder output and the albedo
// trust's t against the CPU network's own, given the CPU's inputs (NetworkInputs, as afn_method);
// and for frames without motion or positions the inputs of a run without the temporal branch
// (the TA input this frame's colour, history01 1), as NetworkInputs prepares them for a model
// without it.
TEST(CudaEmulated, NetworkInputIsTheCpuInputInHalfPrecision)
{
    SequenceInputs noTemporal;
    noTemporal.motion = false;
    noTemporal.position = false;
    const std::pair<const char*, SequenceInputs> cases[]
        = { { "weights_full.afnw", SequenceInputs {} }, { "weights_trust.afnw", SequenceInputs {} },
              { "weights_trust.afnw", noTemporal } };
    for (const auto& [name, sequenceInputs] : cases) {
        SCOPED_TRACE(std::string(name) + ", " + sequenceInputs.name());
        const bool temporal = sequenceInputs.motion || sequenceInputs.position;
        const auto w = testWeights(name);
        const afn::afnet::Network loaded = afn::afnet::networkFromData(w.data(), w.size());
        afn::afnet::Network cpu = loaded;
        const afntest::SyntheticSequence seq(29, 19, 2);
        afntest::EmulatedAfnPipeline emulated(loaded);
        afn::afnet::InputSet use = afn::afnet::InputSet::full();
        use.temporal = temporal;
        emulated.setNetworkInputs(use);
        afntest::FrameGatherer gatherer;
        afntest::CpuFirstStage stages(kAux, kTrust);
        afn::afnet::NetworkInputs inputs;
        afn::Image result, out;
        for (int k = 0; k < 3; ++k) {
            afntest::SequenceFrame in = seq.frame(k, sequenceInputs);
            const afn::Frame& given = gatherer.gather(in);
            stages.run(given);
            const afn::Frame& f = stages.frame;
            const afn::TemporalAccumulator& accumulator = stages.accumulator;
            inputs.prepare(f, use, stages.irradiance, accumulator.color(),
                loaded.hasHistoryInput() ? &accumulator.historyLength() : nullptr);
            cpu.runWholeFrame(inputs.inputs(), result);
            emulated.run(
                given, afn::cuda::frameConstants(f, kReproject, kAccumulation, kTrust, kAux), out);
            const afn::Image x = emulated.networkInput();
            ASSERT_EQ(x.width(), cpu.input().width());
            ASSERT_EQ(x.channels(), cpu.input().channels());
            // Values in [0, 1] rounded to halves: within half a unit in the last place (2^-12).
            EXPECT_LE(afntest::maxAbsDifference(x, cpu.input()), 2.5e-4) << "frame " << k;
            if (loaded.hasHistoryInput() && k > 0 && temporal) { // history01 is not 1 everywhere
                double smallest = 1.0;
                for (std::size_t p = 13; p < x.size(); p += 14)
                    smallest = std::min(smallest, double(x.data()[p]));
                EXPECT_LT(smallest, 0.75) << "frame " << k;
            }
            const afn::Image d1 = emulated.decoderOutput();
            double scale = 0.0;
            for (std::size_t i = 0; i < cpu.decoderOutput().size(); ++i)
                scale = std::max(scale, double(std::fabs(cpu.decoderOutput().data()[i])));
            const double err = afntest::maxAbsDifference(d1, cpu.decoderOutput());
            std::cout << "[ emulated ] " << name << " frame " << k << ": decoder output max |diff| "
                      << err << " (largest value " << scale << ")\n";
            EXPECT_LE(err, 0.02 * scale + 1e-3) << "frame " << k;
            if (loaded.hasAlbedoTrust()) {
                // t = sigmoid(headG(e1)) from e1 in halves: the sigmoid's slope is at most 1/4.
                const afn::Image t = emulated.albedoTrust();
                ASSERT_EQ(t.width(), cpu.albedoTrust().width());
                const double tErr = afntest::maxAbsDifference(t, cpu.albedoTrust());
                std::cout << "[ emulated ] " << name << " frame " << k
                          << ": albedo trust max |diff| " << tErr << "\n";
                EXPECT_LE(tErr, 5e-3) << "frame " << k;
            }
        }
    }
}

namespace {

/// Run the CPU filter and the emulated CUDA engine on a sequence; every frame within tolerance.
/// `weights` empty: both with the built-in models (the one for the sequence's inputs and `spp`,
/// the samples per pixel the frames are said to have; 0 unknown).
void expectFilterParity(const std::vector<char>& weights, int width, int height,
    const SequenceInputs& inputs, int frames, bool noisyAovs = false,
    const std::string& quality = "balanced", int spp = 0)
{
    auto cpu = afn::createFilter("afn");
    afntest::configureAsOnTheGpu(*cpu);
    cpu->params().setString("quality", quality);
    cpu->params().setNumber("spp", spp, AFN_PARAM_INT);
    afn::AuxSettings aux = kAux;
    aux.spp = spp;
    if (!weights.empty())
        cpu->setData(AFN_DATA_WEIGHTS, weights.data(), weights.size());
    // The model and its inputs as AfnCudaFilter chooses them (model_set.h).
    afn::afnet::ModelSet models = weights.empty()
        ? afn::afnet::ModelSet::embedded()
        : afn::afnet::ModelSet::fromData(weights.data(), weights.size());
    const afn::afnet::Model* model = models.choose(afntest::inputSetOf(inputs), spp);
    ASSERT_NE(model, nullptr) << inputs.name() << ": no model for these inputs";
    afntest::EmulatedAfnPipeline emulated(model->net);
    emulated.setNetworkInputs(afn::afnet::inputsToUse(afntest::inputSetOf(inputs), *model));
    // taa=auto and postFilter=auto: on for models trained below 16 spp, as on the CPU.
    emulated.setTaa(model->spp < afn::afnet::kTaaAutoMaxSppExclusive);
    emulated.setPostFilter(model->spp < afn::afnet::kPostFilterAutoMaxSppExclusive);
    emulated.setFastTier(quality == "fast");
    emulated.setHighTier(quality == "high");
    // The accumulation's minimum blend for the model, as both filters choose it (settings.h).
    afn::AccumulationSettings accumulation = kAccumulation;
    accumulation.alphaMin = afn::afnet::accumulationAlphaMin(
        afn::afnet::Settings {}, accumulation.alphaMin, model->spp);
    const afntest::SyntheticSequence seq(width, height, 11);
    afntest::FrameGatherer gatherer;
    gatherer.workSkipping = true; // skip=on, the CPU filter's default
    afn::Image cpuOut(width, height, 3), emuOut;
    const afntest::Tolerance tolerance;
    for (int k = 0; k < frames; ++k) {
        afntest::SequenceFrame in
            = noisyAovs ? noisyAovFrame(seq, k, inputs) : seq.frame(k, inputs);
        afntest::runFrame(*cpu, in, cpuOut);
        const afn::Frame& f = gatherer.gather(in);
        emulated.run(
            f, afn::cuda::frameConstants(f, kReproject, accumulation, kTrust, aux), emuOut);
        const afntest::OutputDifference d = afntest::compareOutputs(emuOut, cpuOut);
        std::cout << "[ emulated ] " << width << "x" << height << " " << inputs.name() << " frame "
                  << k << ": " << d.text() << "\n";
        EXPECT_TRUE(d.within(tolerance))
            << width << "x" << height << " " << inputs.name() << " frame " << k << ": " << d.text();
    }
}

} // namespace

TEST(CudaEmulated, FilterMatchesCpuWithTestWeights)
{
    const auto full = testWeights("weights_full.afnw");
    for (const SequenceInputs& inputs : afntest::parityInputSets())
        if (afntest::cpuRunsTheFullModel(inputs))
            expectFilterParity(full, 37, 21, inputs, 3);
    expectFilterParity(full, 8, 8, SequenceInputs {}, 2);
    expectFilterParity(full, 1, 1, SequenceInputs {}, 2);
}

TEST(CudaEmulated, FilterMatchesCpuWithoutRefinement)
{
    expectFilterParity(testWeights("weights_fusion.afnw"), 45, 27, SequenceInputs {}, 3);
}

// Weights with the history input (x's 14th channel), and with the learned albedo trust as well
// (t after the first encoder level, both colours times s, the output divided by s).
TEST(CudaEmulated, FilterMatchesCpuWithHistoryInputAndAlbedoTrust)
{
    expectFilterParity(testWeights("weights_history.afnw"), 37, 21, SequenceInputs {}, 3);
    const auto trust = testWeights("weights_trust.afnw");
    for (const SequenceInputs& inputs : afntest::parityInputSets())
        if (afntest::cpuRunsTheFullModel(inputs))
            expectFilterParity(trust, 37, 21, inputs, 3);
    expectFilterParity(trust, 8, 8, SequenceInputs {}, 2);
    expectFilterParity(trust, 1, 1, SequenceInputs {}, 2);
}

// The quality tier fast: the fused image as the output (with the albedo trust undone), no
// refinement; and high: the network on the frame and its mirror images, averaged (every row
// computed, work skipping or not).
TEST(CudaEmulated, FilterMatchesCpuInTheFastAndHighTiers)
{
    for (const char* tier : { "fast", "high" })
        for (const char* name :
            { "weights_full.afnw", "weights_trust.afnw", "weights_fusion.afnw" }) {
            SCOPED_TRACE(std::string(tier) + ", " + name);
            expectFilterParity(testWeights(name), 37, 21, SequenceInputs {}, 3, false, tier);
        }
    expectFilterParity(
        testWeights("weights_trust.afnw"), 45, 240, SequenceInputs {}, 2, false, "high");
}

// Work skipping (skip=on, the default): a sky band of 30 rows leaves its first 8-row block beyond
// the TAA's and the post-filter's margins around the rows with work; that block takes the cheap
// path on both engines.
TEST(CudaEmulated, FilterMatchesCpuWhereRowsAreSkipped)
{
    const afntest::SyntheticSequence seq(45, 240, 11);
    afntest::SequenceFrame in = seq.frame(0, SequenceInputs {});
    afntest::FrameGatherer gatherer;
    gatherer.workSkipping = true;
    const afn::Frame& f = gatherer.gather(in);
    afn::Image grown;
    const std::vector<char> rows
        = afn::afnet::computedRows(f.work, afn::afnet::workMargin(true, true), f.height, grown);
    ASSERT_EQ(std::count(rows.begin(), rows.end(), 0), 8) << "the test needs one skipped block";
    for (const char* name : { "weights_full.afnw", "weights_trust.afnw" })
        expectFilterParity(testWeights(name), 45, 240, SequenceInputs {}, 3);
}

// The TAA turned off for a frame and on again (no reset): it starts again without history on both
// engines (a frame without TAA drops it).
TEST(CudaEmulated, FilterMatchesCpuWhenTheTaaIsToggled)
{
    const auto weights = testWeights("weights_full.afnw");
    auto cpu = afn::createFilter("afn");
    configureAsOnTheGpu(*cpu);
    cpu->setData(AFN_DATA_WEIGHTS, weights.data(), weights.size());
    EmulatedAfnPipeline emulated(afn::afnet::networkFromData(weights.data(), weights.size()));
    emulated.setPostFilter(true);
    const SyntheticSequence seq(37, 21, 5);
    FrameGatherer gatherer;
    gatherer.workSkipping = true;
    afn::Image cpuOut(37, 21, 3), emuOut;
    for (int k = 0; k < 5; ++k) {
        const bool taa = k != 2;
        cpu->params().setString("taa", taa ? "on" : "off");
        emulated.setTaa(taa);
        SequenceFrame in = seq.frame(k, SequenceInputs {});
        runFrame(*cpu, in, cpuOut);
        const afn::Frame& f = gatherer.gather(in);
        emulated.run(
            f, afn::cuda::frameConstants(f, kReproject, kAccumulation, kTrust, kAux), emuOut);
        const OutputDifference d = compareOutputs(emuOut, cpuOut);
        EXPECT_TRUE(d.within(Tolerance {})) << "frame " << k << ": " << d.text();
    }
}

// Noisy AOVs (aux=auto decides noisy): the prefiltered buffers reach the network and the
// remodulation as on the CPU.
TEST(CudaEmulated, FilterMatchesCpuWithNoisyAovs)
{
    for (const char* name : { "weights_full.afnw", "weights_trust.afnw" })
        expectFilterParity(testWeights(name), 61, 37, SequenceInputs {}, 4, true);
}

TEST(CudaEmulated, FilterMatchesCpuWithShippedWeights)
{
    const auto shipped = shippedWeights();
    if (shipped.empty())
        GTEST_SKIP() << "weights/afn.afnw is not in this checkout";
    expectFilterParity(shipped, 64, 40, SequenceInputs {}, 3);
    SequenceInputs camera;
    camera.motion = false;
    camera.camera = true;
    expectFilterParity(
        shipped, 51, 33, camera, 2); // The 16-spp model (what the CUDA filter runs for frames near
                                     // 16 spp): no TAA, no post-filter.
    const auto spp16 = shippedWeights("afn-spp16.afnw");
    if (!spp16.empty())
        expectFilterParity(spp16, 64, 40, SequenceInputs {}, 3);
}

// The built-in model of each input set (model_set.h: colour only, colour + albedo + normal, the
// full set), as both engines choose it: inputs the model was not trained for held at their
// neutral values, and a model without albedo on a frame with one filtering the colours times the
// albedo, its output not remodulated (network_inputs.cpp).
TEST(CudaEmulated, FilterMatchesCpuWithTheBuiltInModelOfEachInputSet)
{
    if (afn::afnet::ModelSet::embedded().empty())
        GTEST_SKIP() << "this build has no built-in weights";
    for (const SequenceInputs& inputs : afntest::parityInputSets())
        expectFilterParity({}, 51, 33, inputs, 3);
}

// AFN large (large_graph.h): the test archive at several sizes, in the tier high (its passes) and
// the shipped AFN large (weights/afn-large-spp64.afnw, run with --weights; not built in) at 64 spp,
// the aux prefilter, TAA and post-filter as the CPU runs them at that count.
TEST(CudaEmulated, FilterMatchesCpuWithAfnLarge)
{
    const auto large = testWeights("weights_large.afnw");
    expectFilterParity(large, 37, 21, SequenceInputs {}, 3);
    expectFilterParity(large, 8, 8, SequenceInputs {}, 2);
    expectFilterParity(large, 1, 1, SequenceInputs {}, 2);
    expectFilterParity(large, 37, 21, SequenceInputs {}, 2, false, "high");
    expectFilterParity(large, 37, 21, SequenceInputs {}, 2, false, "fast");
    expectFilterParity(large, 45, 240, SequenceInputs {}, 2); // rows a balanced AFN would skip
    const auto shipped = shippedWeights("afn-large-spp64.afnw");
    if (shipped.empty())
        GTEST_SKIP() << "weights/afn-large-spp64.afnw is not in this checkout";
    expectFilterParity(shipped, 64, 40, SequenceInputs {}, 3, false, "balanced", 64);
    expectFilterParity(shipped, 51, 33, SequenceInputs {}, 3, true, "balanced", 64);
}

// The quarter-resolution scale (quarter_pixel.h): weights with quarter=1 (variant full), every
// row computed, in each tier (fast: the fused output corrected by it).
TEST(CudaEmulated, FilterMatchesCpuWithTheQuarterScale)
{
    const auto quarter = testWeights("weights_quarter.afnw");
    expectFilterParity(quarter, 37, 21, SequenceInputs {}, 3);
    expectFilterParity(quarter, 8, 8, SequenceInputs {}, 2);
    expectFilterParity(quarter, 1, 1, SequenceInputs {}, 2);
    expectFilterParity(quarter, 45, 240, SequenceInputs {}, 2);
    for (const char* tier : { "fast", "high" })
        expectFilterParity(quarter, 37, 21, SequenceInputs {}, 2, false, tier);
}

// The GPU test's cases (tests/gpu) on the emulation: how the tolerance was chosen. Minutes of CPU
// time, so not part of ctest: test_cuda_engine --gtest_also_run_disabled_tests
// --gtest_filter=*Calibration*
TEST(CudaEmulated, DISABLED_CalibrationOnTheGpuParityCases)
{
    for (const afntest::ParityCase& c : afntest::gpuParityCases()) {
        const bool shipped = c.weights == "shipped"; // the built-in models, as tests/gpu
        if (shipped && afn::afnet::ModelSet::embedded().empty())
            continue;
        const std::vector<char> weights = shipped
            ? std::vector<char> {}
            : testWeights(("weights_" + c.weights + ".afnw").c_str());
        if (!shipped && !afntest::cpuRunsTheFullModel(c.inputs)) // one full-input archive
            continue;
        expectFilterParity(
            weights, c.width, c.height, c.inputs, c.frames, false, "balanced", c.spp);
    }
}
