// SPDX-License-Identifier: Apache-2.0
// Packed 3-float pixels (RGB, XYZ) in AVX-512 kernels: one channel of 16 pixels held in three
// vectors (48 floats) and back, for the kernel files that include cpu/avx512.h
// (filter/gather_avx512.cpp, stages/aux_noise_avx512.cpp, stages/reproject_avx512.cpp,
// stages/temporal_accumulation_avx512.cpp, methods/svgf/integrate_avx512.cpp). Pure lane moves: no
// arithmetic.
#pragma once

#include "cpu/avx512.h"

#ifdef AFN_CPU_HAVE_AVX512

namespace afn::cpu {

/// Channel c (0..2) of the 16 packed 3-float pixels in v[0..2].
AFN_CPU_AVX512_INLINE __m512 packedChannel(const __m512* v, int c)
{
    alignas(64) int lo[16], hi[16];
    __mmask16 fromHigh = 0;
    for (int l = 0; l < 16; ++l) {
        const int i = 3 * l + c;
        lo[l] = i < 32 ? i : 0; // from v[0] (0..15) or v[1] (16..31)
        hi[l] = i >= 32 ? i - 32 : 0; // from v[2]
        if (i >= 32)
            fromHigh = static_cast<__mmask16>(fromHigh | (1u << l));
    }
    const __m512 ab = _mm512_permutex2var_ps(v[0], _mm512_load_si512(lo), v[1]);
    return _mm512_mask_permutexvar_ps(ab, fromHigh, _mm512_load_si512(hi), v[2]);
}

/// Channel c of the 16 packed 3-float pixels at p (48 floats, unaligned).
AFN_CPU_AVX512_INLINE __m512 packedChannel(const float* p, int c)
{
    const __m512 v[3] = { _mm512_loadu_ps(p), _mm512_loadu_ps(p + 16), _mm512_loadu_ps(p + 32) };
    return packedChannel(v, c);
}

/// Vector k (0..2) of the packed 3-float layout with each pixel's value of `perPixel` in its 3
/// channels: lane j holds perPixel's lane (16 k + j) / 3.
AFN_CPU_AVX512_INLINE __m512 spreadToPacked(__m512 perPixel, int k)
{
    alignas(64) int idx[16];
    for (int j = 0; j < 16; ++j)
        idx[j] = (16 * k + j) / 3;
    return _mm512_permutexvar_ps(_mm512_load_si512(idx), perPixel);
}

/// Vector k (0..2) of the packed 3-float layout of the 16 pixels whose channels are r, g and b
/// (the inverse of packedChannel): lane j holds channel (16 k + j) % 3 of pixel (16 k + j) / 3.
AFN_CPU_AVX512_INLINE __m512 packedVector(__m512 r, __m512 g, __m512 b, int k)
{
    // Red and green first (index bit 4 picks green), then blue into the remaining lanes.
    alignas(64) int first[16], second[16];
    for (int j = 0; j < 16; ++j) {
        const int i = 16 * k + j, pixel = i / 3, channel = i % 3;
        first[j] = channel == 1 ? 16 + pixel : pixel;
        second[j] = channel == 2 ? 16 + pixel : j;
    }
    const __m512 rg = _mm512_permutex2var_ps(r, _mm512_load_si512(first), g);
    return _mm512_permutex2var_ps(rg, _mm512_load_si512(second), b);
}

} // namespace afn::cpu

#endif
