// SPDX-License-Identifier: Apache-2.0
// AVX-512 softmax + 7x7 filtering (cpu/afn_filter_avx512.h). The 49 logits are 4 vectors; the
// exponential is the portable kernel's Cephes polynomial (cpu/simd.h exp8) on 16 lanes. A kernel
// row covers 7 pixels x 3 channels = 21 contiguous floats of the image, multiplied by the row's
// 7 weights spread to 21 lanes by a permute: 2 FMAs per kernel row instead of 21 scalar ones.
// Pixels within 3 of the border use the scalar kernel (zero padding, methods/afn/fusion.h).
#include "cpu/afn_filter_avx512.h"

#include "cpu/avx512.h"
#include "methods/afn/fusion.h"

#include <cfloat>

namespace afn::cpu {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// exp(x) for x <= 0, as cpu::exp8.
AFN_CPU_AVX512_INLINE __m512 exp16(__m512 x)
{
    x = _mm512_max_ps(x, _mm512_set1_ps(-87.0f));
    const __m512 magic = _mm512_set1_ps(12582912.0f);
    const __m512 t = _mm512_fmadd_ps(x, _mm512_set1_ps(1.44269504088896341f), magic);
    const __m512 n = _mm512_sub_ps(t, magic);
    __m512 r = _mm512_fnmadd_ps(n, _mm512_set1_ps(0.693359375f), x);
    r = _mm512_fnmadd_ps(n, _mm512_set1_ps(-2.12194440e-4f), r);
    __m512 p = _mm512_set1_ps(1.9875691500e-4f);
    p = _mm512_fmadd_ps(p, r, _mm512_set1_ps(1.3981999507e-3f));
    p = _mm512_fmadd_ps(p, r, _mm512_set1_ps(8.3334519073e-3f));
    p = _mm512_fmadd_ps(p, r, _mm512_set1_ps(4.1665795894e-2f));
    p = _mm512_fmadd_ps(p, r, _mm512_set1_ps(1.6666665459e-1f));
    p = _mm512_fmadd_ps(p, r, _mm512_set1_ps(5.0000001201e-1f));
    p = _mm512_fmadd_ps(_mm512_mul_ps(p, r), r, _mm512_add_ps(r, _mm512_set1_ps(1.0f)));
    const __m512i bits = _mm512_slli_epi32(
        _mm512_add_epi32(_mm512_sub_epi32(_mm512_castps_si512(t), _mm512_castps_si512(magic)),
            _mm512_set1_epi32(127)),
        23);
    return _mm512_mul_ps(p, _mm512_castsi512_ps(bits));
}

/// NaN -> -FLT_MAX, +-Inf -> +-FLT_MAX (max returns its second operand for a NaN first one).
AFN_CPU_AVX512_INLINE __m512 finite16(__m512 v)
{
    return _mm512_min_ps(_mm512_max_ps(v, _mm512_set1_ps(-FLT_MAX)), _mm512_set1_ps(FLT_MAX));
}

} // namespace

AFN_CPU_AVX512 void softmaxApplyAvx512(float* l, const Image& img, int x, int y, float* rgb)
{
    constexpr __mmask16 last = 0x0001; // logit 48
    __m512 v0 = finite16(_mm512_loadu_ps(l)), v1 = finite16(_mm512_loadu_ps(l + 16));
    __m512 v2 = finite16(_mm512_loadu_ps(l + 32));
    __m512 v3 = finite16(_mm512_mask_loadu_ps(_mm512_set1_ps(-FLT_MAX), last, l + 48));
    const __m512 m = _mm512_set1_ps(
        _mm512_reduce_max_ps(_mm512_max_ps(_mm512_max_ps(v0, v1), _mm512_max_ps(v2, v3))));
    v0 = exp16(_mm512_sub_ps(v0, m));
    v1 = exp16(_mm512_sub_ps(v1, m));
    v2 = exp16(_mm512_sub_ps(v2, m));
    v3 = _mm512_maskz_mov_ps(last, exp16(_mm512_sub_ps(v3, m)));
    const __m512 inv = _mm512_set1_ps(
        1.0f / _mm512_reduce_add_ps(_mm512_add_ps(_mm512_add_ps(v0, v1), _mm512_add_ps(v2, v3))));
    _mm512_storeu_ps(l, _mm512_mul_ps(v0, inv));
    _mm512_storeu_ps(l + 16, _mm512_mul_ps(v1, inv));
    _mm512_storeu_ps(l + 32, _mm512_mul_ps(v2, inv));
    l[48] = _mm512_cvtss_f32(_mm512_mul_ps(v3, inv));

    constexpr int r = afnet::kKernelSize / 2;
    if (x < r || y < r || x + r >= img.width() || y + r >= img.height()) {
        afnet::applyKernel(img, x, y, l, rgb);
        return;
    }
    // Lane i of the first 16 floats of a kernel row is pixel i / 3; lanes 16..20 are pixels 5, 6.
    const __m512i spreadA = _mm512_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5);
    const __m512i spreadB = _mm512_setr_epi32(5, 5, 6, 6, 6, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    constexpr __mmask16 tail = 0x001f;
    __m512 accA = _mm512_set1_ps(0.0f), accB = _mm512_set1_ps(0.0f);
    // Below the last row, the window's 21 floats plus 11 more lie inside the image: one plain load
    // (lanes 5..15 of accB are never summed); on the last rows a masked one.
    const bool room = y + r + 1 < img.height();
    for (int dy = 0; dy < afnet::kKernelSize; ++dy) {
        const float* p = img.at(x - r, y + dy - r);
        const __m512 k = _mm512_loadu_ps(l + dy * afnet::kKernelSize); // 7 used, 64 readable
        accA = _mm512_fmadd_ps(_mm512_loadu_ps(p), _mm512_permutexvar_ps(spreadA, k), accA);
        const __m512 t = room ? _mm512_loadu_ps(p + 16) : _mm512_maskz_loadu_ps(tail, p + 16);
        accB = _mm512_fmadd_ps(t, _mm512_permutexvar_ps(spreadB, k), accB);
    }
    alignas(64) float s[32];
    _mm512_store_ps(s, accA);
    _mm512_store_ps(s + 16, accB);
    for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (int i = c; i < 21; i += 3)
            sum += s[i];
        rgb[c] = sum;
    }
}

#else

void softmaxApplyAvx512(float* l, const Image& img, int x, int y, float* rgb)
{
    afnet::softmax(l, afnet::kKernelTaps);
    afnet::applyKernel(img, x, y, l, rgb);
}

#endif

} // namespace afn::cpu
