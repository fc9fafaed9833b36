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

} // namespace afntool
