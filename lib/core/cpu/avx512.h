// SPDX-License-Identifier: Apache-2.0
// The common head of the AVX-512 kernels (cpu/conv_avx512.cpp, cpu/afn_filter_avx512.cpp,
// methods/svgf/atrous_avx512.cpp). The build has no -march: such a kernel is compiled for AVX-512
// per function and used only where the running CPU has AVX-512F (cpu/isa.h, checked at run time).
// Where the compiler can do that (GCC or Clang on x86-64), AFN_CPU_HAVE_AVX512 is defined, the
// intrinsics are included, AFN_CPU_AVX512 marks a kernel and AFN_CPU_AVX512_INLINE a helper of one
// (the same target, so that it may use the intrinsics, and always inlined into its caller).
// Elsewhere a kernel file compiles its fallback only. Include it in kernel files only: it silences
// a GCC false positive for the rest of the file.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define AFN_CPU_HAVE_AVX512 1
#define AFN_CPU_AVX512 __attribute__((target("avx512f,avx2,fma")))
#define AFN_CPU_AVX512_INLINE AFN_CPU_AVX512 inline __attribute__((always_inline))
// The bf16 kernels' target (AVX512_BF16 with the AVX-512 they use), for code run only where
// cpu::activeBf16Mode() is not Emulated.
#define AFN_CPU_AVX512_BF16 __attribute__((target("avx512f,avx512bw,avx512vl,avx512bf16,avx2,fma")))
#define AFN_CPU_AVX512_BF16_INLINE AFN_CPU_AVX512_BF16 inline __attribute__((always_inline))
#if defined(__GNUC__) && !defined(__clang__)
// GCC 12's AVX-512 min/max/reduce/roundscale/scalef intrinsics start from _mm512_undefined_ps
// (false positive).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif

namespace afn::cpu {

/// Mask of the first `count` of 16 lanes (all of them from 16 on): the tail of a run of floats.
inline __mmask16 firstLanes(int count)
{
    return count >= 16 ? static_cast<__mmask16>(0xFFFF)
                       : static_cast<__mmask16>((1u << count) - 1u);
}

} // namespace afn::cpu
#endif
