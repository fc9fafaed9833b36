// SPDX-License-Identifier: Apache-2.0
// The accumulation's blend on a static camera's rows, 16 pixels at a time with AVX-512F
// (stages/temporal_accumulation_avx512.h); the function carries its own target attribute. The
// operations are the scalar ones of stages/temporal_accumulation.cpp and blendHistory
// (stages/reproject.h), lane by lane: 1 / (s + 1) (division, correctly rounded as the scalar one),
// the max with alphaMin (no NaN can occur: the history length is finite), prev + alpha * (c - prev)
// without FMA (compiled with -ffp-contract=off, see CMakeLists.txt), then |v| < FLT_MIN flushed to
// 0. The per-pixel alpha is spread to the 3 channels of the packed layout by lane moves. The
// history trust's block sums of such rows likewise: each sum added pixel by pixel in order.
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

AFN_CPU_AVX512 void addOwnHistoryTrust16(const float* c, const float* h, float* sums)
{
    if (!sums)
        return;
    // Lanes 0-2: the channels of the first block's pixel i, lanes 3-5: the second block's; the
    // 8 pixels of each block added in order.
    constexpr __mmask16 kFirst = 0x07, kSecond = 0x38;
    __m512 sc = _mm512_setzero_ps(), sh = sc, sd = sc;
    for (int i = 0; i < kTrustBlock; ++i) {
        // Lane 3 + k of a load from p reads p[3 + k]: p = first pixel of the second block - 3.
        const __m512 cv = _mm512_mask_loadu_ps(
            _mm512_maskz_loadu_ps(kFirst, c + 3 * i), kSecond, c + 3 * (kTrustBlock + i) - 3);
        const __m512 hv = _mm512_mask_loadu_ps(
            _mm512_maskz_loadu_ps(kFirst, h + 3 * i), kSecond, h + 3 * (kTrustBlock + i) - 3);
        const __m512 d = _mm512_sub_ps(cv, hv);
        sc = _mm512_add_ps(sc, cv);
        sh = _mm512_add_ps(sh, hv);
        sd = _mm512_add_ps(sd, _mm512_mul_ps(d, d));
    }
    alignas(64) float vc[16], vh[16], vd[16];
    _mm512_store_ps(vc, sc);
    _mm512_store_ps(vh, sh);
    _mm512_store_ps(vd, sd);
    constexpr int kSums = HistoryTrust::kSums;
    for (int b = 0; b < 2; ++b) {
        float* s = sums + b * kSums;
        s[0] += static_cast<float>(kTrustBlock);
        for (int k = 0; k < 3; ++k) {
            s[1 + k] += vc[3 * b + k];
            s[4 + k] += vh[3 * b + k];
            s[7 + k] += vd[3 * b + k];
        }
    }
}

#else

void addOwnHistoryTrust16(const float*, const float*, float*) { }

void blendOwnHistory16(
    const float*, const float*, const float*, float, const float*, float*, float*)
{
}

#endif

} // namespace afn
