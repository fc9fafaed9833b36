// SPDX-License-Identifier: Apache-2.0
// bf16 GEMM yardstick through oneDNN's matmul primitive (see bf16_gemm_peak.h). Threads as in
// sgemm_peak.cpp (oneDNN from Debian runs on OpenMP).
#include "bf16_gemm_peak.h"

#include "keep_freed_memory_mapped.h"
#include "report.h"

#include <dnnl.h>
#include <omp.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <vector>

namespace afntool {

namespace {

/// bf16 of a float by truncation (the yardstick's inputs; their values do not matter).
std::uint16_t toBf16(float v)
{
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return static_cast<std::uint16_t>(bits >> 16);
}

/// The oneDNN objects of one matmul, released in reverse order of creation.
struct Matmul {
    dnnl_engine_t engine = nullptr;
    dnnl_stream_t stream = nullptr;
    dnnl_primitive_desc_t pd = nullptr;
    dnnl_primitive_t prim = nullptr;
    dnnl_memory_t mem[3] = {};
    ~Matmul()
    {
        for (dnnl_memory_t m : mem)
            if (m)
                dnnl_memory_destroy(m);
        if (prim)
            dnnl_primitive_destroy(prim);
        if (pd)
            dnnl_primitive_desc_destroy(pd);
        if (stream)
            dnnl_stream_destroy(stream);
        if (engine)
            dnnl_engine_destroy(engine);
    }
};

} // namespace

Bf16GemmPeak measureBf16GemmPeak(int threads, int n, int repeats)
{
    Bf16GemmPeak p;
    p.rate.threads = threads < 1 ? 1 : threads;
    p.rate.n = n;
    omp_set_num_threads(p.rate.threads);
    const std::size_t size = static_cast<std::size_t>(n) * n;
    std::vector<std::uint16_t> a(size), b(size);
    std::vector<float> c(size, 0.0f);
    for (std::size_t i = 0; i < size; ++i) {
        a[i] = toBf16(static_cast<float>(i % 97) * (1.0f / 97.0f));
        b[i] = toBf16(static_cast<float>(i % 89) * (1.0f / 89.0f));
    }
    Matmul m;
    const dnnl_dims_t dims = { n, n };
    dnnl_memory_desc_t aMd, bMd, cMd;
    dnnl_matmul_desc_t desc;
    if (dnnl_engine_create(&m.engine, dnnl_cpu, 0) != dnnl_success
        || dnnl_stream_create(&m.stream, m.engine, dnnl_stream_default_flags) != dnnl_success
        || dnnl_memory_desc_init_by_tag(&aMd, 2, dims, dnnl_bf16, dnnl_ab) != dnnl_success
        || dnnl_memory_desc_init_by_tag(&bMd, 2, dims, dnnl_bf16, dnnl_ab) != dnnl_success
        || dnnl_memory_desc_init_by_tag(&cMd, 2, dims, dnnl_f32, dnnl_ab) != dnnl_success
        || dnnl_matmul_desc_init(&desc, &aMd, &bMd, nullptr, &cMd) != dnnl_success) {
        p.why = "oneDNN could not describe a bf16 matmul";
        return p;
    }
    if (dnnl_primitive_desc_create(&m.pd, &desc, nullptr, m.engine, nullptr) != dnnl_success) {
        p.why = "oneDNN has no bf16 matmul for this CPU";
        return p;
    }
    if (dnnl_primitive_create(&m.prim, m.pd) != dnnl_success
        || dnnl_memory_create(&m.mem[0], &aMd, m.engine, a.data()) != dnnl_success
        || dnnl_memory_create(&m.mem[1], &bMd, m.engine, b.data()) != dnnl_success
        || dnnl_memory_create(&m.mem[2], &cMd, m.engine, c.data()) != dnnl_success) {
        p.why = "oneDNN could not create the bf16 matmul";
        return p;
    }
    const dnnl_exec_arg_t args[3] = { { DNNL_ARG_SRC, m.mem[0] }, { DNNL_ARG_WEIGHTS, m.mem[1] },
        { DNNL_ARG_DST, m.mem[2] } };
    const double flop = 2.0 * n * static_cast<double>(n) * n;
    const KeepFreedMemoryMapped keepMapped;
    std::vector<double> rates;
    for (int r = 0; r <= repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        if (dnnl_primitive_execute(m.prim, m.stream, 3, args) != dnnl_success
            || dnnl_stream_wait(m.stream) != dnnl_success) {
            p.why = "the bf16 matmul failed";
            return p;
        }
        const double s
            = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (r > 0) // the first call is a warm-up (thread start, page faults, JIT)
            rates.push_back(flop / s * 1e-9);
    }
    p.available = true;
    p.rate.medianGflops = median(rates);
    for (double v : rates)
        p.rate.bestGflops = v > p.rate.bestGflops ? v : p.rate.bestGflops;
    return p;
}

} // namespace afntool
