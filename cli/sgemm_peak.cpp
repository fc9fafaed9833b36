// SPDX-License-Identifier: Apache-2.0
// dnnl_sgemm yardstick (see sgemm_peak.h). oneDNN 2.x from Debian runs on OpenMP, so its thread
// count is set with omp_set_num_threads (the denoisers run on oneTBB, which this does not touch).
#include "sgemm_peak.h"

#include "cli_error.h"
#include "keep_freed_memory_mapped.h"
#include "report.h"

#include <dnnl.h>
#include <omp.h>

#include <chrono>
#include <string>
#include <vector>

namespace afntool {

SgemmPeak measureSgemmPeak(int threads, int n, int repeats)
{
    SgemmPeak p;
    p.threads = threads < 1 ? 1 : threads;
    p.n = n;
    omp_set_num_threads(p.threads);
    const std::size_t size = static_cast<std::size_t>(n) * n;
    std::vector<float> a(size), b(size), c(size, 0.0f);
    for (std::size_t i = 0; i < size; ++i) {
        a[i] = static_cast<float>(i % 97) * (1.0f / 97.0f);
        b[i] = static_cast<float>(i % 89) * (1.0f / 89.0f);
    }
    const double flop = 2.0 * n * static_cast<double>(n) * n;
    const KeepFreedMemoryMapped keepMapped;
    std::vector<double> rates;
    for (int r = 0; r <= repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const dnnl_status_t st
            = dnnl_sgemm('N', 'N', n, n, n, 1.0f, a.data(), n, b.data(), n, 0.0f, c.data(), n);
        const double s
            = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (st != dnnl_success)
            throw CliError("--benchmark: dnnl_sgemm failed (status " + std::to_string(st) + ")");
        if (r > 0) // the first call is a warm-up (thread start, page faults)
            rates.push_back(flop / s * 1e-9);
    }
    p.medianGflops = median(rates);
    for (double v : rates)
        p.bestGflops = v > p.bestGflops ? v : p.bestGflops;
    return p;
}

} // namespace afntool
