// SPDX-License-Identifier: Apache-2.0
// blendHistory (stages/reproject.h) on 16 lanes, for the AVX-512 kernels that must give the
// scalar blend's bits (stages/temporal_accumulation_avx512.cpp, methods/svgf/integrate_avx512.cpp):
// prev + alpha * (cur - prev) without FMA (the including files are compiled with
// -ffp-contract=off), then |v| < FLT_MIN flushed to 0.
#pragma once

#include "cpu/avx512.h"

#include <cfloat>

#ifdef AFN_CPU_HAVE_AVX512

namespace afn {

AFN_CPU_AVX512_INLINE __m512 blendHistory16(__m512 prev, __m512 cur, __m512 alpha)
{
    const __m512 v = _mm512_add_ps(prev, _mm512_mul_ps(alpha, _mm512_sub_ps(cur, prev)));
    const __mmask16 tiny
        = _mm512_cmp_ps_mask(_mm512_abs_ps(v), _mm512_set1_ps(FLT_MIN), _CMP_LT_OQ);
    return _mm512_mask_mov_ps(v, tiny, _mm512_setzero_ps());
}

} // namespace afn

#endif
