// SPDX-License-Identifier: Apache-2.0
// Helpers of SVGF's AVX-512 kernels (atrous_avx512.cpp, variance_avx512.cpp): the in-image lanes of
// a tap's 16 columns, |v|, a base-2 exponential for the edge-stopping weights, the Rec. 709
// luminance, and the choice of a kernel instance by the guide (only where cpu/avx512.h defines
// AFN_CPU_HAVE_AVX512).
#pragma once

#include "cpu/avx512.h"
#include "methods/svgf/guide.h"

#include <cmath>
#include <type_traits>

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

/// How max(0, n_p . n_q)^sigmaN is evaluated (methods/svgf/guide.h).
struct NormalPower {
    int squarings = -1; ///< sigmaN = 2^squarings: that many squarings
    unsigned integer = 0; ///< else an integer sigmaN: binary powering
    bool integral = false;
    float sigmaN = 0.0f; ///< else std::pow per lane
};

inline NormalPower normalPowerOf(const Guide& g)
{
    NormalPower np;
    np.sigmaN = g.sigmaN;
    np.integral = g.integerSigmaN;
    if (g.integerSigmaN) {
        np.integer = static_cast<unsigned>(g.sigmaN);
        if (np.integer != 0 && (np.integer & (np.integer - 1)) == 0)
            np.squarings = __builtin_ctz(np.integer);
    }
    return np;
}

/// max(0, d)^sigmaN (max(0, NaN) = 0, as std::fmax); kSquarings >= 0: sigmaN = 2^kSquarings (the
/// default 128 = 2^7, unrolled), -1: as `np` says.
template <int kSquarings>
AFN_CPU_AVX512_INLINE __m512 normalPower16(const NormalPower& np, __m512 d)
{
    d = _mm512_max_ps(d, _mm512_setzero_ps());
    const int squarings = kSquarings >= 0 ? kSquarings : np.squarings;
    if (squarings >= 0) {
        for (int k = 0; k < squarings; ++k)
            d = _mm512_mul_ps(d, d);
        return d;
    }
    if (np.integral) {
        __m512 result = _mm512_set1_ps(1.0f);
        for (unsigned e = np.integer; e; e >>= 1u) {
            if (e & 1u)
                result = _mm512_mul_ps(result, d);
            d = _mm512_mul_ps(d, d);
        }
        return result;
    }
    alignas(64) float v[16];
    _mm512_store_ps(v, d);
    for (float& x : v)
        x = std::pow(x, np.sigmaN);
    return _mm512_load_ps(v);
}

/// 0.2126 r + 0.7152 g + 0.0722 b of 16 pixels (the multiply, then two multiply-adds).
AFN_CPU_AVX512_INLINE __m512 luminance16(__m512 r, __m512 g, __m512 b)
{
    __m512 lum = _mm512_mul_ps(_mm512_set1_ps(0.2126f), r);
    lum = _mm512_fmadd_ps(_mm512_set1_ps(0.7152f), g, lum);
    return _mm512_fmadd_ps(_mm512_set1_ps(0.0722f), b, lum);
}

/// Calls run(hasNormal, hasDepth, squarings) with std::integral_constant arguments for the
/// guide's buffers: squarings 7 where normals take the default sigmaN 128 (= 2^7, unrolled),
/// else -1 (the kernel's general power).
template <typename Run> void forGuide(const Guide& g, Run&& run)
{
    using std::integral_constant;
    const bool default128 = g.integerSigmaN && g.sigmaN == 128.0f;
    using Yes = integral_constant<bool, true>;
    using No = integral_constant<bool, false>;
    using Seven = integral_constant<int, 7>;
    using General = integral_constant<int, -1>;
    if (g.hasNormal && g.hasDepth && default128)
        run(Yes {}, Yes {}, Seven {});
    else if (g.hasNormal && g.hasDepth)
        run(Yes {}, Yes {}, General {});
    else if (g.hasNormal && default128)
        run(Yes {}, No {}, Seven {});
    else if (g.hasNormal)
        run(Yes {}, No {}, General {});
    else if (g.hasDepth)
        run(No {}, Yes {}, General {});
    else
        run(No {}, No {}, General {});
}

} // namespace afn::svgf

#endif
