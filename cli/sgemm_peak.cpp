// SPDX-License-Identifier: Apache-2.0
// dnnl_sgemm yardstick (see sgemm_peak.h). oneDNN 2.x from Debian runs on OpenMP, so its thread
// count is set with omp_set_num_threads (the denoisers run on oneTBB, which this does not touch).
#include "sgemm_peak.h"

#include "cli_error.h"
#include "report.h"

#include <dnnl.h>
#include <omp.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <chrono>
#include <string>
#include <vector>

namespace afntool {

namespace {

/// dnnl_sgemm allocates its packing buffers (MiBs) on every call. glibc serves blocks that large
/// with mmap and unmaps them on free, so each call page-faults its scratch memory in again: on
/// the 2-core development machine that held the 2-thread rate at 224-240 GFLOP/s, against 400
/// with the same library when freed memory stays mapped (measured with jemalloc preloaded, and
/// with this guard). The yardstick is meant as the machine's GEMM peak, not glibc's page-fault
/// rate, so while it runs freed memory stays in the heap; glibc's default thresholds (128 KiB)
/// are set back and the memory returned afterwards, before any denoiser is timed.
class KeepFreedMemoryMapped {
public:
    KeepFreedMemoryMapped()
    {
#if defined(__GLIBC__)
        mallopt(M_MMAP_THRESHOLD, 32 << 20); // glibc's largest allowed value on 64-bit
        mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
    }
    ~KeepFreedMemoryMapped()
    {
#if defined(__GLIBC__)
        mallopt(M_MMAP_THRESHOLD, 128 << 10);
        mallopt(M_TRIM_THRESHOLD, 128 << 10);
        malloc_trim(0);
#endif
    }
    KeepFreedMemoryMapped(const KeepFreedMemoryMapped&) = delete;
    KeepFreedMemoryMapped& operator=(const KeepFreedMemoryMapped&) = delete;
};

} // namespace

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
