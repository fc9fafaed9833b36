// SPDX-License-Identifier: Apache-2.0
// The CUDA engine's kernel code, run on the CPU through the host emulation (emulated_pipeline.h),
// against the CPU engine: the first stage bit for bit, the network input to half precision, and
// the whole filter within the documented tolerance (afn_output_compare.h) on synthetic sequences
// of several sizes, input sets and weights. Built in every configuration: a GPU is not needed.
#include "afn_output_compare.h"
#include "afn_parity_cases.h"
#include "afn_test_util.h"
#include "cuda/frame_constants.h"
#include "emulated_pipeline.h"
#include "filter/registry.h"
#include "methods/afn/network_inputs.h"
#include "methods/afn/post_filter.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"
#include "stages/aux_prefilter.h"
#include "stages/demodulate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <random>

namespace {

using afntest::readBytes;
using afntest::SequenceInputs;

std::vector<char> testWeights(const char* name)
{
    const auto bytes = readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/" + name);
    EXPECT_FALSE(bytes.empty()) << name;
    return bytes;
}

std::vector<char> shippedWeights()
{
    return readBytes(std::string(AFN_SOURCE_DIR) + "/weights/afn.afnw");
}

const afn::ReprojectSettings kReproject {};
const afn::AccumulationSettings kAccumulation {};
const afn::HistoryTrustSettings kTrust {}; ///< the default, antilag 1
const afn::AuxSettings kAux {}; ///< the default, auto at an unknown sample count

} // namespace

// Aux prefilter, demodulation, reprojection, history trust and accumulation bit for bit, on every
// input set, with the trust off, at its default and stronger, on a sequence whose left half
// brightens 3x from frame 3 on (a light switched on): the trust cuts history there, and the cut
// share is the CPU's.
TEST(CudaEmulated, FirstStageIsTheCpuStagesBitForBit)
{
    const afn::afnet::Network net = [] {
        const auto w = testWeights("weights_full.afnw");
        return afn::afnet::networkFromData(w.data(), w.size());
    }();
    for (const float antilag : { 0.0f, 1.0f, 2.5f })
        for (const SequenceInputs& inputs : afntest::parityInputSets()) {
            SCOPED_TRACE(inputs.name() + ", antilag " + std::to_string(antilag));
            const afntest::SyntheticSequence seq(75, 43, 5);
            afntest::EmulatedAfnPipeline emulated(net);
            afntest::FrameGatherer gatherer;
            afntest::CpuFirstStage cpu(kAux, { antilag });
            const afn::Image& irradiance = cpu.irradiance;
            const afn::TemporalAccumulator& accumulator = cpu.accumulator;
            afn::Image out;
            double largestCut = 0.0;
            for (int k = 0; k < 6; ++k) {
                afntest::SequenceFrame in = seq.frame(k, inputs);
                if (k >= 3)
                    for (int y = 0; y < in.color.height(); ++y)
                        for (int x = 0; x < in.color.width() / 2; ++x)
                            for (int c = 0; c < 3; ++c)
                                in.color(x, y, c) *= 3.0f;
                const afn::Frame& given = gatherer.gather(in);
                cpu.run(given);
                emulated.run(given,
                    afn::cuda::frameConstants(given, kReproject, kAccumulation, { antilag }, kAux),
                    out);
                ASSERT_EQ(0,
                    std::memcmp(
                        irradiance.data(), emulated.irradiance().data(), 4 * irradiance.size()))
                    << "frame " << k;
                ASSERT_EQ(0,
                    std::memcmp(accumulator.color().data(), emulated.accumulated().data(),
                        4 * irradiance.size()))
                    << "frame " << k << ": max |diff| "
                    << afntest::maxAbsDifference(accumulator.color(), emulated.accumulated());
                ASSERT_EQ(0,
                    std::memcmp(accumulator.historyLength().data(), emulated.historyLength().data(),
                        4 * emulated.historyLength().size()))
                    << "frame " << k;
                EXPECT_EQ(accumulator.trust().cutShare(), emulated.cutShare()) << "frame " << k;
                largestCut = std::max(largestCut, emulated.cutShare());
            }
            if (antilag > 0.0f && afntest::cpuRunsTheFullModel(inputs))
                EXPECT_GT(largestCut, 0.1) << "the switch cut no history";
            if (antilag == 0.0f)
                EXPECT_EQ(largestCut, 0.0);
        }
}

namespace {

/// Frame k of `seq` with 1-spp-like noise in its auxiliary buffers inside a rectangle (an object
/// whose AOVs follow random specular bounces): each pixel's albedo scaled by a factor in
/// [0.2, 1.8], its normal tilted by up to 0.6 per axis (renormalised), its depth moved by up to
/// 10 %.
afntest::SequenceFrame noisyAovFrame(
    const afntest::SyntheticSequence& seq, int k, const SequenceInputs& inputs)
{
    afntest::SequenceFrame in = seq.frame(k, inputs);
    std::mt19937 rng(100u + static_cast<unsigned>(k));
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const int w = in.color.width(), h = in.color.height();
    for (int y = h / 4; y < 3 * h / 4; ++y)
        for (int x = w / 4; x < w / 2; ++x) {
            const float scale = 0.2f + 1.6f * u(rng);
            if (!in.albedo.empty())
                for (int c = 0; c < 3; ++c)
                    in.albedo(x, y, c) *= scale;
            float n[3], len2 = 0.0f;
            for (int c = 0; c < 3; ++c) {
                n[c] = 0.6f * (2.0f * u(rng) - 1.0f)
                    + (in.normal.empty() ? 0.0f : in.normal(x, y, c));
                len2 += n[c] * n[c];
            }
            if (!in.normal.empty() && len2 > 0.0f)
                for (int c = 0; c < 3; ++c)
                    in.normal(x, y, c) = n[c] / std::sqrt(len2);
            const float dz = 1.0f + 0.2f * (u(rng) - 0.5f);
            if (!in.depth.empty() && in.depth(x, y, 0) < 1e9f)
                in.depth(x, y, 0) *= dz;
        }
    return in;
}

bool sameBits(const afn::Image& a, const afn::Image& b)
{
    return a.size() == b.size()
        && (a.size() == 0 || std::memcmp(a.data(), b.data(), 4 * a.size()) == 0);
}

} // namespace

// The aux prefilter's albedo, normal and depth bit for bit against the CPU stage (its flags,
// 5x5 means, decision, reliability and the albedo's history through the taps of the prefiltered
// geometry), in every mode: auto at 1 spp (decided noisy), auto at 16 spp (grain limited), noisy
// and clean, on every input set, with noisy AOVs in a rectangle; the decision and the shares are
// the CPU's, and every mode but clean changes the albedo.
TEST(CudaEmulated, AuxPrefilterIsTheCpuStageBitForBit)
{
    using M = afn::AuxSettings::Mode;
    const afn::afnet::Network net = [] {
        const auto w = testWeights("weights_full.afnw");
        return afn::afnet::networkFromData(w.data(), w.size());
    }();
    const afn::AuxSettings modes[]
        = { { M::Auto, 0 }, { M::Auto, 16 }, { M::Noisy, 0 }, { M::Clean, 0 } };
    for (const afn::AuxSettings& mode : modes)
        for (const SequenceInputs& inputs : afntest::parityInputSets()) {
            SCOPED_TRACE(inputs.name() + ", aux mode " + std::to_string(static_cast<int>(mode.aux))
                + ", spp " + std::to_string(mode.spp));
            const afntest::SyntheticSequence seq(61, 37, 9);
            afntest::EmulatedAfnPipeline emulated(net);
            afntest::FrameGatherer gatherer;
            afntest::CpuFirstStage cpu(mode, kTrust);
            afn::Image out;
            bool changed = false;
            for (int k = 0; k < 4; ++k) {
                afntest::SequenceFrame in = noisyAovFrame(seq, k, inputs);
                const afn::Frame& given = gatherer.gather(in);
                cpu.run(given);
                emulated.run(given,
                    afn::cuda::frameConstants(given, kReproject, kAccumulation, kTrust, mode), out);
                const afn::Frame& f = cpu.frame;
                EXPECT_TRUE(sameBits(emulated.albedo(), f.albedo)) << "albedo, frame " << k;
                EXPECT_TRUE(sameBits(emulated.normal(), f.normal)) << "normal, frame " << k;
                EXPECT_TRUE(sameBits(emulated.depth(), f.depth)) << "depth, frame " << k;
                const afn::AuxReport& r = cpu.aux.report();
                EXPECT_EQ(emulated.auxState().noisy != 0, r.noisy) << "frame " << k;
                EXPECT_EQ(emulated.auxState().grainLimited != 0, r.grainLimited) << "frame " << k;
                if (!cpu.aux.sharesPending() && f.hasAlbedo())
                    EXPECT_EQ(emulated.auxState().counts[0] / (double(f.width) * f.height),
                        r.albedoSpeckle)
                        << "frame " << k;
                changed = changed || !sameBits(f.albedo, given.albedo);
            }
            if (inputs.albedo)
                EXPECT_EQ(changed, mode.aux != M::Clean);
        }
}

// The post-filter's guides and half-passes against the CPU filter (methods/afn/post_filter.h) on
// the same radiance and guides: frames from 1x1 to 61x37 (taps clamped at every border, steps
// beyond the frame), sky and invalid normals included, with and without the noise inputs. The CPU
// contracts multiply-adds in some instruction-set clones: equal to float rounding.
TEST(CudaEmulated, PostFilterIsTheCpuFilter)
{
    for (const auto& [w, h] :
        std::vector<std::pair<int, int>> { { 1, 1 }, { 5, 3 }, { 37, 23 }, { 61, 37 } })
        for (const bool noise : { false, true }) {
            SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + (noise ? ", noise" : ""));
            const afntest::SyntheticSequence seq(w, h, 13);
            afntest::SequenceFrame in = noisyAovFrame(seq, 2, SequenceInputs {});
            afntest::FrameGatherer gatherer;
            const afn::Frame& f = gatherer.gather(in);
            afn::Image radiance = f.color, irradiance, length(w, h, 1);
            afn::demodulate(f, irradiance);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    length(x, y, 0) = static_cast<float>(1 + (x * 7 + y * 3) % 12);
            afn::afnet::PostFilterGuides guides;
            guides.albedo = &f.albedo;
            guides.normal = &f.normal;
            guides.depth = &f.depth;
            if (noise) {
                guides.noise.irradiance = &irradiance;
                guides.noise.historyLength = &length;
                guides.noise.maxSamples = 9.0f;
            }
            afn::afnet::PostFilterWorkspace workspace;
            afn::Image cpu;
            afn::afnet::edgeAwarePostFilter(radiance, guides, workspace, cpu);

            const std::size_t n = static_cast<std::size_t>(w) * h;
            std::vector<float> planes(9 * n), s0(3 * n), s1(3 * n);
            std::vector<float> colour(radiance.data(), radiance.data() + 3 * n);
            afn::cuda::PostFilterSources src;
            src.width = w;
            src.height = h;
            src.albedo = f.albedo.data();
            src.normal = f.normal.data();
            src.depth = f.depth.data();
            src.irradiance = noise ? irradiance.data() : nullptr;
            src.historyLength = noise ? length.data() : nullptr;
            src.maxSamples = 9.0f;
            afn::cuda::PostFilterPlanes g;
            float** ordered[9] = { &g.a0, &g.a1, &g.a2, &g.n0, &g.n1, &g.n2, &g.nv, &g.z, &g.ls };
            for (int k = 0; k < 9; ++k)
                *ordered[k] = planes.data() + k * n;
            afntest::emulatePostFilter(src, g, colour.data(), s0.data(), s1.data());
            double worst = 0.0;
            bool changed = false;
            for (std::size_t k = 0; k < 3 * n; ++k) {
                const double a = colour[k], b = cpu.data()[k];
                worst = std::max(worst, std::fabs(a - b) / (std::fabs(b) + 1e-3));
                changed = changed || cpu.data()[k] != radiance.data()[k];
            }
            std::cout << "[ emulated ] post-filter " << w << "x" << h << (noise ? " noise" : "")
                      << ": max relative difference " << worst << "\n";
            EXPECT_LE(worst, 1e-4);
            if (n > 1)
                EXPECT_TRUE(changed) << "the CPU filter left the frame as it was";
        }
}

// The network input (with history01 where the weights read it), the decoder output and the albedo
// trust's t against the CPU network's own, given the CPU's inputs (NetworkInputs, as afn_method).
TEST(CudaEmulated, NetworkInputIsTheCpuInputInHalfPrecision)
{
    for (const char* name : { "weights_full.afnw", "weights_trust.afnw" }) {
        SCOPED_TRACE(name);
        const auto w = testWeights(name);
        const afn::afnet::Network loaded = afn::afnet::networkFromData(w.data(), w.size());
        afn::afnet::Network cpu = loaded;
        const afntest::SyntheticSequence seq(29, 19, 2);
        afntest::EmulatedAfnPipeline emulated(loaded);
        afntest::FrameGatherer gatherer;
        afntest::CpuFirstStage stages(kAux, kTrust);
        afn::afnet::NetworkInputs inputs;
        afn::Image result, out;
        for (int k = 0; k < 3; ++k) {
            afntest::SequenceFrame in = seq.frame(k, SequenceInputs {});
            const afn::Frame& given = gatherer.gather(in);
            stages.run(given);
            const afn::Frame& f = stages.frame;
            const afn::TemporalAccumulator& accumulator = stages.accumulator;
            inputs.prepare(f, afn::afnet::InputSet::full(), stages.irradiance, accumulator.color(),
                loaded.hasHistoryInput() ? &accumulator.historyLength() : nullptr);
            cpu.runWholeFrame(inputs.inputs(), result);
            emulated.run(
                given, afn::cuda::frameConstants(f, kReproject, kAccumulation, kTrust, kAux), out);
            const afn::Image x = emulated.networkInput();
            ASSERT_EQ(x.width(), cpu.input().width());
            ASSERT_EQ(x.channels(), cpu.input().channels());
            // Values in [0, 1] rounded to halves: within half a unit in the last place (2^-12).
            EXPECT_LE(afntest::maxAbsDifference(x, cpu.input()), 2.5e-4) << "frame " << k;
            if (loaded.hasHistoryInput() && k > 0) { // history01 is not 1 everywhere
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
void expectFilterParity(const std::vector<char>& weights, int width, int height,
    const SequenceInputs& inputs, int frames, bool noisyAovs = false)
{
    auto cpu = afn::createFilter("afn");
    afntest::configureAsOnTheGpu(*cpu);
    cpu->setData(AFN_DATA_WEIGHTS, weights.data(), weights.size());
    const afn::afnet::Network net = afn::afnet::networkFromData(weights.data(), weights.size());
    afntest::EmulatedAfnPipeline emulated(net);
    // postFilter=auto: on for weights trained below 16 spp, as on the CPU.
    emulated.setPostFilter(net.trainedSpp() < afn::afnet::kPostFilterAutoMaxSppExclusive);
    const afntest::SyntheticSequence seq(width, height, 11);
    afntest::FrameGatherer gatherer;
    afn::Image cpuOut(width, height, 3), emuOut;
    const afntest::Tolerance tolerance;
    for (int k = 0; k < frames; ++k) {
        afntest::SequenceFrame in
            = noisyAovs ? noisyAovFrame(seq, k, inputs) : seq.frame(k, inputs);
        afntest::runFrame(*cpu, in, cpuOut);
        const afn::Frame& f = gatherer.gather(in);
        emulated.run(
            f, afn::cuda::frameConstants(f, kReproject, kAccumulation, kTrust, kAux), emuOut);
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
    expectFilterParity(shipped, 51, 33, camera, 2);
}

// The GPU test's cases (tests/gpu) on the emulation: how the tolerance was chosen. Minutes of CPU
// time, so not part of ctest: test_cuda_engine --gtest_also_run_disabled_tests
// --gtest_filter=*Calibration*
TEST(CudaEmulated, DISABLED_CalibrationOnTheGpuParityCases)
{
    for (const afntest::ParityCase& c : afntest::gpuParityCases()) {
        std::vector<char> weights = c.weights == "shipped"
            ? shippedWeights()
            : testWeights(("weights_" + c.weights + ".afnw").c_str());
        if (weights.empty() || !afntest::cpuRunsTheFullModel(c.inputs)) // as tests/gpu
            continue;
        expectFilterParity(weights, c.width, c.height, c.inputs, c.frames);
    }
}
