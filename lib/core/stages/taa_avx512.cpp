// SPDX-License-Identifier: Apache-2.0
// The TAA's row kernel with AVX-512F, 16 pixels at a time (stages/taa_rows.h): the operations of
// blendRowPortable in the same order (compiled without FMA contraction), so the same bits.
// min/max: _mm512_min_ps returns its second operand where std::min returns its first, which
// differs only for equal values of opposite sign or NaN; the planes hold neither (radiance and
// history are >= 0 and never -0, and YCoCg of such values is never -0).
#include "cpu/avx512.h"
#include "stages/taa_rows.h"

#include <cfloat>

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

AFN_CPU_AVX512_INLINE __m512 load(const float* p, int x, __mmask16 m)
{
    return _mm512_maskz_loadu_ps(m, p + x);
}

} // namespace

AFN_CPU_AVX512 void blendRowAvx512(const TaaBlendRow& r, int w)
{
    const __m512 alpha = _mm512_set1_ps(r.alpha);
    const __m512 half = _mm512_set1_ps(0.5f), quarter = _mm512_set1_ps(0.25f);
    const __m512 minusQuarter = _mm512_set1_ps(-0.25f), zero = _mm512_setzero_ps();
    const __m512 fltMin = _mm512_set1_ps(FLT_MIN);
    const __m512i absMask = _mm512_set1_epi32(0x7fffffff);
    for (int x = 0; x < w; x += 16) {
        const __mmask16 m = w - x >= 16 ? __mmask16(0xffff) : __mmask16((1u << (w - x)) - 1u);
        __m512 lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            const __m512 cLo = load(r.centre->lo[k], x, m), cHi = load(r.centre->hi[k], x, m);
            const __m512 aV = load(r.above->v[k], x, m), bV = load(r.below->v[k], x, m);
            const __m512 boxLo = _mm512_min_ps(
                _mm512_min_ps(load(r.above->lo[k], x, m), cLo), load(r.below->lo[k], x, m));
            const __m512 boxHi = _mm512_max_ps(
                _mm512_max_ps(load(r.above->hi[k], x, m), cHi), load(r.below->hi[k], x, m));
            const __m512 crossLo = _mm512_min_ps(_mm512_min_ps(cLo, aV), bV);
            const __m512 crossHi = _mm512_max_ps(_mm512_max_ps(cHi, aV), bV);
            lo[k] = _mm512_mul_ps(half, _mm512_add_ps(boxLo, crossLo));
            hi[k] = _mm512_mul_ps(half, _mm512_add_ps(boxHi, crossHi));
        }
        const __m512 h0 = load(r.hist[0], x, m), h1 = load(r.hist[1], x, m),
                     h2 = load(r.hist[2], x, m);
        __m512 hy[3];
        hy[0] = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(quarter, h0), _mm512_mul_ps(half, h1)),
            _mm512_mul_ps(quarter, h2));
        hy[1] = _mm512_sub_ps(_mm512_mul_ps(half, h0), _mm512_mul_ps(half, h2));
        hy[2]
            = _mm512_sub_ps(_mm512_add_ps(_mm512_mul_ps(minusQuarter, h0), _mm512_mul_ps(half, h1)),
                _mm512_mul_ps(quarter, h2));
        __m512 q[3];
        __mmask16 outside = 0;
        for (int k = 0; k < 3; ++k) {
            const __mmask16 below = _mm512_cmp_ps_mask(hy[k], lo[k], _CMP_LT_OQ);
            const __mmask16 above = _mm512_cmp_ps_mask(hy[k], hi[k], _CMP_GT_OQ);
            outside |= below | above;
            q[k] = _mm512_mask_blend_ps(below, _mm512_mask_blend_ps(above, hy[k], hi[k]), lo[k]);
        }
        __m512 hist[3];
        hist[0] = _mm512_mask_blend_ps(outside, h0, _mm512_sub_ps(_mm512_add_ps(q[0], q[1]), q[2]));
        hist[1] = _mm512_mask_blend_ps(outside, h1, _mm512_add_ps(q[0], q[2]));
        hist[2] = _mm512_mask_blend_ps(outside, h2, _mm512_sub_ps(_mm512_sub_ps(q[0], q[1]), q[2]));
        const __mmask16 has = _mm512_mask_cmp_ps_mask(m, load(r.has, x, m), zero, _CMP_NEQ_UQ);
        for (int k = 0; k < 3; ++k) {
            const __m512 c = load(r.cur[k], x, m);
            __m512 v = _mm512_add_ps(hist[k], _mm512_mul_ps(alpha, _mm512_sub_ps(c, hist[k])));
            const __m512 a = _mm512_castsi512_ps(_mm512_and_si512(_mm512_castps_si512(v), absMask));
            // |v| < FLT_MIN -> 0, then 0 < v ? v : 0 (both zero the same lanes' complement).
            const __mmask16 keep = _mm512_cmp_ps_mask(a, fltMin, _CMP_NLT_UQ)
                & _mm512_cmp_ps_mask(zero, v, _CMP_LT_OQ);
            v = _mm512_maskz_mov_ps(keep, v);
            _mm512_mask_storeu_ps(r.out[k] + x, m, _mm512_mask_blend_ps(has, c, v));
        }
    }
}

#else

void blendRowAvx512(const TaaBlendRow& r, int w)
{
    blendRowPortable(r, w);
}

#endif

} // namespace afn
