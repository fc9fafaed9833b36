// SPDX-License-Identifier: Apache-2.0
// The gather's normal conversion, 16 pixels at a time with AVX-512F (filter/gather_avx512.h); the
// function carries its own target attribute. Operation for operation the scalar code of
// filter/gather.cpp: p.z * zSign, len = sqrt((x x + y y) + z z) without FMA, inv = 1 / len where
// len > 1e-12 (else 0), each channel times inv (no FMA: compiled with -ffp-contract=off). The
// lengths are computed on the channels taken apart; the products are done in the interleaved layout
// with inv spread to the 3 channels.
#include "filter/gather_avx512.h"
#include "cpu/avx512.h"
#include "cpu/avx512_rgb.h"

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// Lane j of vector k (of 3) holds channel (16 k + j) % 3 of pixel (16 k + j) / 3: spread the
/// per-pixel values of `perPixel` so.
AFN_CPU_AVX512_INLINE __m512 spread(__m512 perPixel, int k)
{
    alignas(64) int idx[16];
    for (int j = 0; j < 16; ++j)
        idx[j] = (16 * k + j) / 3;
    return _mm512_permutexvar_ps(_mm512_load_si512(idx), perPixel);
}

} // namespace

AFN_CPU_AVX512 void normalizeNormals16(float* p, float zSign)
{
    __m512 v[3];
    for (int k = 0; k < 3; ++k)
        v[k] = _mm512_loadu_ps(p + 16 * k);
    // z * zSign in the interleaved layout (lanes of channel 2), then the lengths.
    for (int k = 0; k < 3; ++k) {
        __mmask16 z = 0;
        for (int j = 0; j < 16; ++j)
            if ((16 * k + j) % 3 == 2)
                z = static_cast<__mmask16>(z | (1u << j));
        v[k] = _mm512_mask_mul_ps(v[k], z, v[k], _mm512_set1_ps(zSign));
    }
    const __m512 x = cpu::packedChannel(v, 0), y = cpu::packedChannel(v, 1),
                 zc = cpu::packedChannel(v, 2);
    const __m512 len = _mm512_sqrt_ps(_mm512_add_ps(
        _mm512_add_ps(_mm512_mul_ps(x, x), _mm512_mul_ps(y, y)), _mm512_mul_ps(zc, zc)));
    const __mmask16 ok = _mm512_cmp_ps_mask(len, _mm512_set1_ps(1e-12f), _CMP_GT_OQ);
    const __m512 inv = _mm512_maskz_div_ps(ok, _mm512_set1_ps(1.0f), len);
    for (int k = 0; k < 3; ++k)
        _mm512_storeu_ps(p + 16 * k, _mm512_mul_ps(v[k], spread(inv, k)));
}

#else

void normalizeNormals16(float*, float) { }

#endif

} // namespace afn
