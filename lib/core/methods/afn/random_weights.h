// SPDX-License-Identifier: Apache-2.0
// Randomly initialised AFN weights of a given architecture (benchmarks: timings do not depend on
// the weight values). Uniform(-1/sqrt(fan_in), 1/sqrt(fan_in)), like PyTorch's default init range.
#pragma once

#include "nn/weights.h"

#include <array>
#include <string>

namespace afn::afnet {

/// Widths of an AFN model (training/afn/model.py AFNConfig; defaults = the shipped architecture).
struct Architecture {
    std::array<int, 3> enc { 16, 32, 64 }; ///< e1, e2, e3 channels
    std::array<int, 2> dec { 32, 24 }; ///< d2, d1 channels
    int refine = 16; ///< refinement hidden channels
    std::string variant = "full"; ///< full | fusion | 1spp | ta
    bool albedoTrust = false; ///< the learned albedo trust's head (albedo_trust.h; full, fusion)
};

/// Build random weights for `arch` with a fixed seed.
nn::WeightsArchive randomWeights(const Architecture& arch, unsigned seed = 0);

} // namespace afn::afnet
