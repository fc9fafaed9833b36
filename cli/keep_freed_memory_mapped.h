// SPDX-License-Identifier: Apache-2.0
// A scope in which glibc keeps freed memory mapped: for the dnnl_sgemm yardstick (afntool
// --benchmark and bench/bench_afn.cpp), whose per-call scratch glibc would otherwise unmap and
// page-fault in again on every call. Header-only so that both tools share it.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace afntool {

/// dnnl_sgemm allocates its packing buffers (MiBs) on every call. glibc serves blocks that large
/// with mmap and unmaps them on free, so calls page-fault their scratch memory in again. Measured
/// on the 2-core development machine (idle, 2026-12-01), best / median of 7 calls, GFLOP/s:
///   1 thread:  glibc 204 / 115, with this scope 205 / 204, jemalloc preloaded 206 / 205;
///   2 threads: glibc 224 / 220, with this scope about the same, jemalloc preloaded 391 / 387.
/// So this scope steadies the 1-thread figure; the 2-thread one stays ~40 % below what the same
/// library reaches on jemalloc (per-thread arenas; MALLOC_ARENA_MAX=1 did not help either), and
/// afntool prints that caveat beside the yardstick. glibc's default thresholds (128 KiB) are set
/// back and the memory returned afterwards, before any denoiser is timed.
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

} // namespace afntool
