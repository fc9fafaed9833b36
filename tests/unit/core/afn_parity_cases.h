// SPDX-License-Identifier: Apache-2.0
// The sequences on which the CUDA afn engine is compared with the CPU engine (tests/gpu), also
// run through the host emulation of the kernels to calibrate the tolerance on machines without a
// GPU (test_cuda_engine --gtest_also_run_disabled_tests --gtest_filter=*Calibration*).
#pragma once

#include "afn_synthetic_sequence.h"
#include "filter/filter.h"
#include "methods/afn/input_set.h"
#include "stages/aux_prefilter.h"
#include "stages/demodulate.h"
#include "stages/reproject.h"
#include "stages/temporal_accumulation.h"

#include <string>
#include <vector>

namespace afntest {

/// Set a CPU afn filter's convolutions to fp32 on every CPU (auto runs bf16 where the CPU has it):
/// the reference the CUDA engine's half precision is measured against (docs/gpu.md).
inline void configureAsOnTheGpu(afn::Filter& cpu)
{
    cpu.params().setString("precision", "fp32");
}

/// The CPU's stages before the afn network, in Filter::runStages()'s order and default
/// reprojection and accumulation settings: the aux prefilter's prepare, the reprojection, its
/// finish, demodulation, accumulation (with the history trust); the reference of the CUDA
/// engine's first stage.
struct CpuFirstStage {
    afn::Reprojector reprojector;
    afn::TemporalAccumulator accumulator;
    afn::AuxPrefilter aux;
    afn::Frame frame; ///< the last frame after the prefilter
    afn::Image irradiance;

    CpuFirstStage(const afn::AuxSettings& auxSettings, const afn::HistoryTrustSettings& trust)
    {
        accumulator.setTrustSettings(trust);
        aux.setSettings(auxSettings);
    }
    void run(const afn::Frame& given)
    {
        frame = given;
        if (frame.frameIndex == 0) {
            reprojector.reset();
            accumulator.reset();
            aux.reset();
        }
        aux.prepare(frame);
        reprojector.compute(frame);
        aux.finish(frame, &reprojector);
        afn::demodulate(frame, irradiance);
        accumulator.accumulate(reprojector, irradiance);
        reprojector.storeGeometry(frame);
    }
};

struct ParityCase {
    /// "full", "fusion", "trust", "large", "quarter" (tests/data/afn_parity: weights_trust has
    /// the history input and the albedo trust, weights_large is AFN large, weights_quarter has
    /// the quarter-resolution scale; the full input set only) or
    /// "shipped" (the built-in models, weights/: the one for the sequence's input set and `spp`)
    std::string weights;
    int width = 0;
    int height = 0;
    SequenceInputs inputs;
    int frames = 3;
    int spp = 0; ///< the samples per pixel the frames are said to have (the `spp` parameter)
    std::string name() const
    {
        return weights + " " + std::to_string(width) + "x" + std::to_string(height) + " "
            + inputs.name() + (spp > 0 ? " " + std::to_string(spp) + " spp" : "");
    }
};

/// Every input set the engines must agree on: all AOVs with motion; positions and cameras
/// without motion; depth without positions; colour only; no albedo; albedo without normal (a
/// model without albedo on a frame with one).
inline std::vector<SequenceInputs> parityInputSets()
{
    SequenceInputs all;
    SequenceInputs camera = all;
    camera.motion = false;
    camera.camera = true;
    SequenceInputs depthOnly;
    depthOnly.position = false;
    depthOnly.motion = false;
    SequenceInputs colorOnly { false, false, false, false, false, false };
    SequenceInputs noAlbedo = all;
    noAlbedo.albedo = false;
    SequenceInputs albedoOnly = all;
    albedoOnly.normal = false;
    albedoOnly.depth = false;
    return { all, camera, depthOnly, colorOnly, noAlbedo, albedoOnly };
}

/// The input set (methods/afn/input_set.h) of a sequence's frames.
inline afn::afnet::InputSet inputSetOf(const SequenceInputs& in)
{
    return { in.albedo, in.normal, in.depth, in.motion || (in.position && in.camera) };
}

/// Whether the CPU filter can run the full-input model on `in`: albedo, normal and depth, with a
/// temporal history (motion, or positions with a camera) or single-frame without one. For fewer
/// inputs it runs the model for that input set (methods/afn/model_set.h), or refuses when only
/// the full one is loaded (weights given as one archive).
inline bool cpuRunsTheFullModel(const SequenceInputs& in)
{
    const afn::afnet::InputSet s = inputSetOf(in);
    return s.albedo && s.normal && s.depth;
}

/// The GPU parity cases: sizes from 1 x 1 to 1280 x 720 (odd ones included), each input set,
/// the committed test archives (variants "full", "fusion" and "large"; "full" with the history
/// input and the albedo trust, and with the quarter scale) and the shipped models (the built-in
/// choice at 64 spp: the 16-spp model).
inline std::vector<ParityCase> gpuParityCases()
{
    std::vector<ParityCase> cases;
    const SequenceInputs all;
    for (const auto& [w, h] : std::vector<std::pair<int, int>> {
             { 1, 1 }, { 8, 8 }, { 37, 21 }, { 64, 48 }, { 129, 67 }, { 256, 144 } })
        cases.push_back({ "full", w, h, all, 3 });
    for (const SequenceInputs& in : parityInputSets())
        cases.push_back({ "full", 97, 61, in, 3 });
    cases.push_back({ "fusion", 45, 27, all, 3 });
    cases.push_back({ "fusion", 200, 120, all, 3 });
    for (const auto& [w, h] :
        std::vector<std::pair<int, int>> { { 1, 1 }, { 37, 21 }, { 129, 67 } })
        cases.push_back({ "trust", w, h, all, 3 });
    for (const SequenceInputs& in : parityInputSets()) // the built-in model of each input set
        cases.push_back({ "shipped", 161, 91, in, 3 });
    for (const auto& [w, h] :
        std::vector<std::pair<int, int>> { { 1, 1 }, { 37, 21 }, { 129, 67 } })
        cases.push_back({ "large", w, h, all, 3 });
    cases.push_back({ "quarter", 37, 21, all, 3 });
    cases.push_back({ "quarter", 129, 67, all, 3 });
    cases.push_back({ "shipped", 161, 91, all, 3, 64 }); // the built-in choice at 64 spp
    cases.push_back({ "shipped", 333, 187, all, 4 });
    cases.push_back({ "shipped", 640, 360, all, 3 });
    cases.push_back({ "shipped", 1280, 720, all, 3 });
    return cases;
}

} // namespace afntest
