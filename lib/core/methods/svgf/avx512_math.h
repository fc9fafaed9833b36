// SPDX-License-Identifier: Apache-2.0
// Helpers of SVGF's AVX-512 kernels (atrous_avx512.cpp, variance_avx512.cpp): the in-image lanes of
// a tap's 16 columns, |v|, and a base-2 exponential for the edge-stopping weights (only where
// cpu/avx512.h defines AFN_CPU_HAVE_AVX512).
#pragma once

#include "cpu/avx512.h"

#ifdef AFN_CPU_HAVE_AVX512

namespace afn::svgf {

constexpr float kLog2e = 1.44269504088896341f;

/// Lanes l of 16 with 0 <= qx0 + l < width.
inline __mmask16 columnsInImage(int qx0, int width)
{
    const int lo = qx0 < 0 ? -qx0 : 0;
    const int hi = width - qx0 < 16 ? width - qx0 : 16;
    if (hi <= lo)
        return 0;
    const unsigned bits = (hi == 16 ? 0xffffu : (1u << hi) - 1u) & ~((1u << lo) - 1u);
    return static_cast<__mmask16>(bits);
}

/// 2^a for a <= 0 (finite results for a >= -126; lanes below are flushed or masked by callers):
/// 2^floor(a) (vscalefps) * p(a - floor(a)), p a degree-5 minimax polynomial on [0, 1) (relative
/// error 1.6e-7 with FMA).
AFN_CPU_AVX512_INLINE __m512 exp2v(__m512 a)
{
    const __m512 fl = _mm512_roundscale_ps(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    const __m512 f = _mm512_sub_ps(a, fl);
    __m512 p = _mm512_set1_ps(1.877576695e-03f);
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(8.989340626e-03f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(5.582631752e-02f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(2.401536107e-01f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(6.931530833e-01f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(9.999999404e-01f));
    return _mm512_scalef_ps(p, fl);
}

AFN_CPU_AVX512_INLINE __m512 absv(__m512 v)
{
    return _mm512_castsi512_ps(
        _mm512_and_si512(_mm512_castps_si512(v), _mm512_set1_epi32(0x7fffffff)));
}

} // namespace afn::svgf

#endif
