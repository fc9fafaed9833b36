// SPDX-License-Identifier: Apache-2.0
// The AFN input tone map with AVX-512F, operation for operation the scalar toneMap
// (methods/afn/tone_map.cpp; the method in tone_map.h): getexp/getmant give the exponent and the
// mantissa in [1, 2) exactly as frexp does (denormals included); q = floor(e / 11) (exactly, from
// a multiply: below) and j = e - 11 q are exact; the polynomials are evaluated in the same order
// without FMA (-ffp-contract=off, see CMakeLists.txt); the table is read by a lane permute; scalef
// multiplies by 2^(5 q) as ldexp. toneMapRunAvx512Bf16 is the cheaper approximation for inputs
// of a network that runs in bf16 (tone_map.h).
#include "methods/afn/tone_map_avx512.h"

#include "cpu/avx512.h"
#include "methods/afn/tone_map_poly.h"

namespace afn::afnet {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// The tone map's limits for 16 values: which are > 0 (false for NaN) and which >= 1; `inside`
/// holds x where it is in (0, 1) and 0.5 (any value in range) elsewhere, whose result limited()
/// then replaces.
struct Limits {
    __mmask16 positive, atLeastOne;
    __m512 inside;
};

AFN_CPU_AVX512_INLINE Limits limitsOf(__m512 x)
{
    const __mmask16 positive = _mm512_cmp_ps_mask(x, _mm512_set1_ps(0.0f), _CMP_GT_OQ);
    const __mmask16 atLeastOne = _mm512_cmp_ps_mask(x, _mm512_set1_ps(1.0f), _CMP_GE_OQ);
    return { positive, atLeastOne,
        _mm512_mask_mov_ps(_mm512_set1_ps(0.5f), positive & ~atLeastOne, x) };
}

/// y where x is in (0, 1), 0 where x <= 0 or NaN, 1 where x >= 1.
AFN_CPU_AVX512_INLINE __m512 limited(const Limits& l, __m512 y)
{
    y = _mm512_mask_mov_ps(_mm512_set1_ps(0.0f), l.positive, y);
    return _mm512_mask_mov_ps(y, l.atLeastOne, _mm512_set1_ps(1.0f));
}

} // namespace

AFN_CPU_AVX512 int toneMapRunAvx512(const float* in, float* out, int n)
{
    using namespace tonemap;
    const __m512 one = _mm512_set1_ps(1.0f), two = _mm512_set1_ps(2.0f),
                 half = _mm512_set1_ps(0.5f), eleven = _mm512_set1_ps(11.0f),
                 five = _mm512_set1_ps(5.0f);
    const __m512 table = _mm512_loadu_ps(kPow2Fifths);
    int i = 0;
    for (; i + 16 <= n; i += 16) {
        const Limits lim = limitsOf(_mm512_loadu_ps(in + i));
        const __m512 xs = lim.inside;
        __m512 m = _mm512_getmant_ps(xs, _MM_MANT_NORM_1_2, _MM_MANT_SIGN_zero);
        __m512 e = _mm512_getexp_ps(xs);
        const __mmask16 big = _mm512_cmp_ps_mask(m, _mm512_set1_ps(kSqrt2), _CMP_GE_OQ);
        m = _mm512_mask_mul_ps(m, big, m, half);
        e = _mm512_mask_add_ps(e, big, e, one);
        // floor(e / 11) as floor((e + 1/2) / 11) with a multiply: e is an integer in [-149, 0],
        // so (e + 1/2) / 11 is at least 1/22 from any integer and the product's error (below
        // 2e-6) cannot change the floor.
        const __m512 q = _mm512_roundscale_ps(
            _mm512_mul_ps(_mm512_add_ps(e, half), _mm512_set1_ps(1.0f / 11.0f)),
            _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        const __m512 j = _mm512_sub_ps(e, _mm512_mul_ps(eleven, q));
        const __m512 t = _mm512_permutexvar_ps(_mm512_cvttps_epi32(j), table);
        const __m512 s = _mm512_div_ps(_mm512_sub_ps(m, one), _mm512_add_ps(m, one));
        const __m512 s2 = _mm512_mul_ps(s, s);
        __m512 l = _mm512_mul_ps(s2, _mm512_set1_ps(kLogC9));
        l = _mm512_mul_ps(s2, _mm512_add_ps(_mm512_set1_ps(kLogC7), l));
        l = _mm512_mul_ps(s2, _mm512_add_ps(_mm512_set1_ps(kLogC5), l));
        l = _mm512_mul_ps(s2, _mm512_add_ps(_mm512_set1_ps(kLogC3), l));
        const __m512 lnm = _mm512_mul_ps(_mm512_mul_ps(two, s), _mm512_add_ps(one, l));
        const __m512 u = _mm512_mul_ps(lnm, _mm512_set1_ps(kInvGamma));
        __m512 p = _mm512_mul_ps(u, _mm512_set1_ps(kExpC6));
        p = _mm512_mul_ps(u, _mm512_add_ps(_mm512_set1_ps(kExpC5), p));
        p = _mm512_mul_ps(u, _mm512_add_ps(_mm512_set1_ps(kExpC4), p));
        p = _mm512_mul_ps(u, _mm512_add_ps(_mm512_set1_ps(kExpC3), p));
        p = _mm512_mul_ps(u, _mm512_add_ps(_mm512_set1_ps(kExpC2), p));
        p = _mm512_mul_ps(u, _mm512_add_ps(one, p));
        p = _mm512_add_ps(one, p);
        _mm512_storeu_ps(
            out + i, limited(lim, _mm512_scalef_ps(_mm512_mul_ps(t, p), _mm512_mul_ps(five, q))));
    }
    return i;
}

AFN_CPU_AVX512 int toneMapRunAvx512Bf16(const float* in, float* out, int n)
{
    using namespace tonemap;
    const __m512 one = _mm512_set1_ps(1.0f);
    int i = 0;
    for (; i + 16 <= n; i += 16) {
        const Limits lim = limitsOf(_mm512_loadu_ps(in + i));
        const __m512 xs = lim.inside;
        // log2 x = e + log2(1 + t), m = 1 + t in [1, 2).
        const __m512 t
            = _mm512_sub_ps(_mm512_getmant_ps(xs, _MM_MANT_NORM_1_2, _MM_MANT_SIGN_zero), one);
        __m512 l = _mm512_set1_ps(kLog2C[5]);
        for (int k = 4; k >= 0; --k)
            l = _mm512_fmadd_ps(l, t, _mm512_set1_ps(kLog2C[k]));
        const __m512 g = _mm512_set1_ps(kInvGamma);
        const __m512 u = _mm512_fmadd_ps(_mm512_getexp_ps(xs), g, _mm512_mul_ps(l, g));
        // 2^u = 2^nu 2^f, |f| <= 1/2.
        const __m512 nu = _mm512_roundscale_ps(u, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
        const __m512 f = _mm512_sub_ps(u, nu);
        __m512 p = _mm512_set1_ps(kExp2C[4]);
        for (int k = 3; k >= 0; --k)
            p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(kExp2C[k]));
        _mm512_storeu_ps(out + i, limited(lim, _mm512_scalef_ps(p, nu)));
    }
    return i;
}

#else

int toneMapRunAvx512(const float*, float*, int)
{
    return 0;
}

int toneMapRunAvx512Bf16(const float*, float*, int)
{
    return 0;
}

#endif

} // namespace afn::afnet
