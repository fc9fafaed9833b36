// SPDX-License-Identifier: Apache-2.0
// The machine's own dense bf16 GEMM rate (bf16 inputs, fp32 sums and output), measured with
// oneDNN's matmul primitive: the yardstick of afn's convolutions when they run in bf16
// (precision=bf16, methods/afn/settings.h), as dnnl_sgemm (sgemm_peak.h) is for fp32. oneDNN 2.x
// has no bf16 GEMM function, so the primitive API is used. Not product pixel math.
#pragma once

#include "sgemm_peak.h"

#include <string>

namespace afntool {

/// The bf16 rate, or why there is none (oneDNN has no bf16 matmul for this CPU).
struct Bf16GemmPeak {
    bool available = false;
    std::string why; ///< when not available
    SgemmPeak rate; ///< threads, n, best and median GFLOP/s (2 FLOP per multiply-add)
};

/// Measure on `threads` threads (>= 1): `repeats` timed calls after one warm-up call.
Bf16GemmPeak measureBf16GemmPeak(int threads, int n = 1024, int repeats = 7);

} // namespace afntool
