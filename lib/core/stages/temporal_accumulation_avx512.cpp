// SPDX-License-Identifier: Apache-2.0
// The accumulation's blend on a static camera's rows, 16 pixels at a time with AVX-512F
// (stages/temporal_accumulation_avx512.h); the function carries its own target attribute. The
// operations are the scalar ones of stages/temporal_accumulation.cpp and blendHistory
// (stages/reproject.h), lane by lane: 1 / (s + 1) (division, correctly rounded as the scalar one),
// the max with alphaMin (no NaN can occur: the history length is finite), prev + alpha * (c - prev)
// without FMA (compiled with -ffp-contract=off, see CMakeLists.txt), then |v| < FLT_MIN flushed to
// 0. The per-pixel alpha is spread to the 3 channels of the packed layout by lane moves.
#include "stages/temporal_accumulation_avx512.h"

#include "cpu/avx512.h"
#include "cpu/avx512_rgb.h"
#include "stages/blend_history_avx512.h"
#include "stages/temporal_accumulation.h"

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

AFN_CPU_AVX512 void blendOwnHistory16(const float* c, const float* prev, const float* prevSpp,
    float alphaMin, const float* trust, float* acc, float* spp)
{
    const __m512 one = _mm512_set1_ps(1.0f);
    const __m512 s = _mm512_loadu_ps(prevSpp);
    __m512 s1 = _mm512_add_ps(s, one);
    // std::max(1 / (s + 1), alphaMin): alphaMin where 1 / (s + 1) < alphaMin.
    const __m512 inv = _mm512_div_ps(one, s1);
    const __m512 alphaMinV = _mm512_set1_ps(alphaMin);
    __m512 alpha
        = _mm512_mask_mov_ps(inv, _mm512_cmp_ps_mask(inv, alphaMinV, _CMP_LT_OQ), alphaMinV);
    if (trust) {
        // Where t < 1: alpha + (1 - alpha) * (1 - t), and the length s * t (+ 1 below).
        const __m512 t = _mm512_loadu_ps(trust);
        const __mmask16 cut = _mm512_cmp_ps_mask(t, one, _CMP_LT_OQ);
        const __m512 raised
            = _mm512_add_ps(alpha, _mm512_mul_ps(_mm512_sub_ps(one, alpha), _mm512_sub_ps(one, t)));
        alpha = _mm512_mask_mov_ps(alpha, cut, raised);
        s1 = _mm512_mask_mov_ps(s1, cut, _mm512_add_ps(_mm512_mul_ps(s, t), one));
    }
    // alpha < 1 ? min(s + 1, kMaxHistoryLength) : 1 (std::min(a, b) is b where b < a).
    const __m512 cap = _mm512_set1_ps(kMaxHistoryLength);
    const __m512 capped = _mm512_mask_mov_ps(s1, _mm512_cmp_ps_mask(cap, s1, _CMP_LT_OQ), cap);
    _mm512_storeu_ps(
        spp, _mm512_mask_mov_ps(one, _mm512_cmp_ps_mask(alpha, one, _CMP_LT_OQ), capped));
    for (int k = 0; k < 3; ++k)
        _mm512_storeu_ps(acc + 16 * k,
            blendHistory16(_mm512_loadu_ps(prev + 16 * k), _mm512_loadu_ps(c + 16 * k),
                cpu::spreadToPacked(alpha, k)));
}

#else

void blendOwnHistory16(
    const float*, const float*, const float*, float, const float*, float*, float*)
{
}

#endif

} // namespace afn
