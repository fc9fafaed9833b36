// SPDX-License-Identifier: Apache-2.0
// The CUDA engine's per-pixel stages, run on the CPU through the host emulation
// (emulated_pipeline.h), against the CPU's: the aux prefilter, the first stage with the history
// trust and the output TAA bit for bit, the post-filter to float rounding. Built in every
// configuration: a GPU is not needed.
#include "afn_output_compare.h"
#include "afn_parity_cases.h"
#include "cuda/frame_constants.h"
#include "emulated_pipeline.h"
#include "emulated_test_util.h"
#include "methods/afn/post_filter.h"
#include "methods/afn/weights_source.h"
#include "stages/demodulate.h"
#include "stages/taa.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>

using namespace afntest;

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
                afntest::SequenceFrame in = lightSwitchedOnFrame(seq, k, inputs);
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

// The output TAA bit for bit against the CPU's (stages/taa.h) on the emulated pipeline's own
// radiance: the CPU's TemporalAntialiasing with the CPU stages' reprojection and history trust,
// the trust off and on, on a sequence whose left half brightens 3x from frame 3 on and with a
// camera (positions) as well as motion vectors.
TEST(CudaEmulated, TaaIsTheCpuTaa)
{
    const auto w = testWeights("weights_full.afnw");
    const afn::afnet::Network net = afn::afnet::networkFromData(w.data(), w.size());
    SequenceInputs camera;
    camera.motion = false;
    camera.camera = true;
    for (const float antilag : { 0.0f, 1.0f })
        for (const SequenceInputs& inputs : { SequenceInputs {}, camera }) {
            SCOPED_TRACE(inputs.name() + ", antilag " + std::to_string(antilag));
            const afntest::SyntheticSequence seq(53, 31, 21);
            afntest::EmulatedAfnPipeline emulated(net);
            emulated.setTaa(true);
            afntest::FrameGatherer gatherer;
            afntest::CpuFirstStage cpu(kAux, { antilag });
            afn::TemporalAntialiasing taa;
            afn::Image spare, out;
            bool differs = false;
            for (int k = 0; k < 6; ++k) {
                afntest::SequenceFrame in = lightSwitchedOnFrame(seq, k, inputs);
                const afn::Frame& given = gatherer.gather(in);
                cpu.run(given);
                if (k == 0)
                    taa.reset();
                emulated.run(given,
                    afn::cuda::frameConstants(given, kReproject, kAccumulation, { antilag }, kAux),
                    out);
                const afn::Image& expected = taa.apply(
                    cpu.reprojector, emulated.radiance(), 0.7f, spare, &cpu.accumulator.trust());
                ASSERT_TRUE(sameBits(out, expected))
                    << "frame " << k << ": max |diff| " << afntest::maxAbsDifference(out, expected);
                differs = differs || !sameBits(out, emulated.radiance());
            }
            EXPECT_TRUE(differs) << "the TAA left every frame as it was";
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
            afntest::emulatePostFilter(src, g, colour.data(), colour.data(), s0.data(), s1.data());
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
