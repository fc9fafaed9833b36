// SPDX-License-Identifier: Apache-2.0
// The demodulation's AVX-512F kernels (stages/demodulate_avx512.h); the functions carry their own
// target attribute. Each value takes the scalar operations of stages/demodulate.cpp: max(a, eps)
// as std::max (a < eps ? eps : a), one IEEE division or product, then the clamp v > 0 ? min(v,
// kMaxIrradiance) : 0 (NaN gives 0), so the results are the same bits. Masked loads and stores do
// the tail of a run.
#include "stages/demodulate_avx512.h"
#include "cpu/avx512.h"
#include "stages/demodulate.h"

#include <algorithm>
#include <cstdint>

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

using cpu::firstLanes;

/// std::max(a, kAlbedoEpsilon): the second operand where a < eps, else a.
AFN_CPU_AVX512_INLINE __m512 albedoFloor(__m512 a)
{
    const __m512 eps = _mm512_set1_ps(kAlbedoEpsilon);
    return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(a, eps, _CMP_LT_OQ), a, eps);
}

/// v > 0 ? std::min(v, kMaxIrradiance) : 0, with std::min(v, m) = m < v ? m : v.
AFN_CPU_AVX512_INLINE __m512 clampIrradiance(__m512 v)
{
    const __m512 m = _mm512_set1_ps(kMaxIrradiance);
    const __m512 capped = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(m, v, _CMP_LT_OQ), v, m);
    return _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(v, _mm512_setzero_ps(), _CMP_GT_OQ), capped);
}

/// Values i.. of the remodulated run (m: the lanes in the run).
AFN_CPU_AVX512_INLINE __m512 remodulated(
    const float* v, const float* a, int i, __mmask16 m, bool plain)
{
    __m512 f = _mm512_maskz_loadu_ps(m, a + i);
    if (!plain)
        f = albedoFloor(f);
    return _mm512_mul_ps(clampIrradiance(_mm512_maskz_loadu_ps(m, v + i)), f);
}

} // namespace

AFN_CPU_AVX512 void demodulateRunAvx512(const float* c, const float* a, float* o, int n)
{
    for (int i = 0; i < n; i += 16) {
        const __mmask16 m = firstLanes(n - i);
        __m512 v = _mm512_maskz_loadu_ps(m, c + i);
        if (a) // masked-off lanes divide 0 by the floor: no exception is raised or stored
            v = _mm512_div_ps(v, albedoFloor(_mm512_maskz_loadu_ps(m, a + i)));
        _mm512_mask_storeu_ps(o + i, m, clampIrradiance(v));
    }
}

AFN_CPU_AVX512 void remodulateRunAvx512(
    const float* v, const float* a, float* o, int n, bool plain, bool stream)
{
    int i = 0;
    const auto addr = reinterpret_cast<std::uintptr_t>(o);
    if (stream && addr % sizeof(float) == 0) {
        // Up to the first 64-byte boundary with ordinary stores, then whole aligned vectors
        // streamed past the caches, the tail again with ordinary (masked) stores.
        const int head = std::min(n, static_cast<int>((64 - addr % 64) % 64 / sizeof(float)));
        if (head > 0)
            _mm512_mask_storeu_ps(
                o, firstLanes(head), remodulated(v, a, 0, firstLanes(head), plain));
        for (i = head; i + 16 <= n; i += 16)
            _mm512_stream_ps(o + i, remodulated(v, a, i, firstLanes(16), plain));
        _mm_sfence(); // the streamed stores are visible before the caller reads the buffer
    }
    for (; i < n; i += 16) {
        const __mmask16 m = firstLanes(n - i);
        _mm512_mask_storeu_ps(o + i, m, remodulated(v, a, i, m, plain));
    }
}

#else

void demodulateRunAvx512(const float*, const float*, float*, int) { }
void remodulateRunAvx512(const float*, const float*, float*, int, bool, bool) { }

#endif

} // namespace afn
