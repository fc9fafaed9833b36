// SPDX-License-Identifier: Apache-2.0
// SVGF's temporal integration on a static camera's rows, 16 pixels at a time with AVX-512F
// (methods/svgf/integrate_avx512.h); the function carries its own target attribute. The
// operations are the scalar ones of Denoiser::integrate (methods/svgf/temporal.cpp), lane by
// lane: the luminance as (0.2126 r + 0.7152 g) + 0.0722 b, std::min / std::max as their
// comparisons, 1 / len a division (correctly rounded as the scalar one), and blendHistory's
// prev + a (c - prev) without FMA (compiled with -ffp-contract=off, see CMakeLists.txt), then
// |v| < FLT_MIN flushed to 0. tests/unit/core/methods/svgf/test_svgf_integrate.cpp compares the
// two paths bit for bit.
#include "methods/svgf/integrate_avx512.h"

#include "cpu/avx512.h"
#include "cpu/avx512_rgb.h"
#include "stages/blend_history_avx512.h"
#include "stages/temporal_accumulation_avx512.h"

namespace afn::svgf {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

AFN_CPU_AVX512_INLINE __m512 luminance16(__m512 r, __m512 g, __m512 b)
{
    return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(0.2126f), r),
                             _mm512_mul_ps(_mm512_set1_ps(0.7152f), g)),
        _mm512_mul_ps(_mm512_set1_ps(0.0722f), b));
}

/// std::max(floor, v): v where floor < v.
AFN_CPU_AVX512_INLINE __m512 maxOf(__m512 floor, __m512 v)
{
    return _mm512_mask_mov_ps(floor, _mm512_cmp_ps_mask(floor, v, _CMP_LT_OQ), v);
}

} // namespace

AFN_CPU_AVX512 void integrateOwnHistory16(const float* c, const float* const* prev, float alpha,
    float momentsAlpha, const float* trust, float* const* out)
{
    const __m512 packed[3]
        = { _mm512_loadu_ps(c), _mm512_loadu_ps(c + 16), _mm512_loadu_ps(c + 32) };
    __m512 cur[3];
    for (int k = 0; k < 3; ++k)
        cur[k] = cpu::packedChannel(packed, k);
    const __m512 l = luminance16(cur[0], cur[1], cur[2]);
    const __m512 m[2] = { l, _mm512_mul_ps(l, l) };
    // len = std::min(prev + 1, 255): 255 where 255 < prev + 1.
    const __m512 cap = _mm512_set1_ps(255.0f);
    __m512 len = _mm512_add_ps(_mm512_loadu_ps(prev[5]), _mm512_set1_ps(1.0f));
    len = _mm512_mask_mov_ps(len, _mm512_cmp_ps_mask(cap, len, _CMP_LT_OQ), cap);
    const __m512 one = _mm512_set1_ps(1.0f);
    const __m512 inv = _mm512_div_ps(one, len);
    __m512 a = maxOf(_mm512_set1_ps(alpha), inv);
    __m512 am = maxOf(_mm512_set1_ps(momentsAlpha), inv);
    if (trust) {
        // Where t < 1: both alphas + (1 - alpha) (1 - t), len = min(ceil(prev length t) + 1, 255).
        const __m512 t = _mm512_loadu_ps(trust);
        const __mmask16 lower = _mm512_cmp_ps_mask(t, one, _CMP_LT_OQ);
        const __m512 cut = _mm512_sub_ps(one, t);
        a = _mm512_mask_mov_ps(
            a, lower, _mm512_add_ps(a, _mm512_mul_ps(_mm512_sub_ps(one, a), cut)));
        am = _mm512_mask_mov_ps(
            am, lower, _mm512_add_ps(am, _mm512_mul_ps(_mm512_sub_ps(one, am), cut)));
        __m512 cutLen
            = _mm512_add_ps(_mm512_roundscale_ps(_mm512_mul_ps(_mm512_loadu_ps(prev[5]), t),
                                _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC),
                one);
        cutLen = _mm512_mask_mov_ps(cutLen, _mm512_cmp_ps_mask(cap, cutLen, _CMP_LT_OQ), cap);
        len = _mm512_mask_mov_ps(len, lower, cutLen);
    }
    __m512 o[3];
    for (int k = 0; k < 3; ++k) {
        o[k] = blendHistory16(_mm512_loadu_ps(prev[k]), cur[k], a);
        _mm512_storeu_ps(out[k], o[k]);
    }
    for (int k = 0; k < 2; ++k)
        _mm512_storeu_ps(out[3 + k], blendHistory16(_mm512_loadu_ps(prev[3 + k]), m[k], am));
    _mm512_storeu_ps(out[5], len);
    _mm512_storeu_ps(out[6], luminance16(o[0], o[1], o[2]));
}

AFN_CPU_AVX512 void addOwnTrust16(const float* c, const float* const* prev, float* sums)
{
    if (!sums)
        return;
    const __m512 p[3]
        = { _mm512_loadu_ps(prev[0]), _mm512_loadu_ps(prev[1]), _mm512_loadu_ps(prev[2]) };
    const __m512 l = luminance16(p[0], p[1], p[2]);
    // l > 0 ? m1 / l : 1 (a NaN luminance fails the test, as in the scalar code).
    const __m512 s = _mm512_mask_div_ps(_mm512_set1_ps(1.0f),
        _mm512_cmp_ps_mask(l, _mm512_setzero_ps(), _CMP_GT_OQ), _mm512_loadu_ps(prev[3]), l);
    const __m512 hr = _mm512_mul_ps(p[0], s), hg = _mm512_mul_ps(p[1], s),
                 hb = _mm512_mul_ps(p[2], s);
    alignas(64) float h[48];
    for (int k = 0; k < 3; ++k)
        _mm512_store_ps(h + 16 * k, cpu::packedVector(hr, hg, hb, k));
    addOwnHistoryTrust16(c, h, sums);
}

#else

void addOwnTrust16(const float*, const float* const*, float*) { }

void integrateOwnHistory16(
    const float*, const float* const*, float, float, const float*, float* const*)
{
}

#endif

} // namespace afn::svgf
