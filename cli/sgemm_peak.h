// SPDX-License-Identifier: Apache-2.0
// The machine's own dense fp32 GEMM rate, measured with oneDNN's dnnl_sgemm (the reference beside
// which --benchmark:size reports afn's GFLOP/s). Not product pixel math: a yardstick.
#pragma once

namespace afntool {

/// dnnl_sgemm on n x n x n matrices: `repeats` timed calls after one warm-up call.
struct SgemmPeak {
    int threads = 0; ///< OpenMP threads oneDNN ran on
    int n = 0; ///< M = N = K
    double bestGflops = 0.0; ///< fastest call (the peak)
    double medianGflops = 0.0; ///< median call (the load on a shared machine shows here)
};

/// Measure on `threads` threads (>= 1). Throws CliError if oneDNN reports an error.
SgemmPeak measureSgemmPeak(int threads, int n = 1024, int repeats = 7);

} // namespace afntool
