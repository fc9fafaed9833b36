// SPDX-License-Identifier: Apache-2.0
// AVX-512 softmax + 7x7 filtering (cpu/afn_filter_avx512.h), 16 pixels of a row per call, one
// pixel per lane: the 49 logits of the 16 pixels are turned tap-major (three 16 x 16 transposes of
// the pixels' logit rows and one gather for the last tap; 48 gathers were 12 % slower on the AMD
// EPYC and 2 % faster on the Intel Xeon, docs/experiments.md), then the maximum, the
// exponentials (the portable kernel's Cephes polynomial, cpu/simd.h exp8, on 16 lanes) and their
// sum run lane-wise, and each tap is then 3 FMAs (one per channel) on 16 pixels of the
// channel-planar image rows (PlanarRows), whose zero pad and zero rows give the zero padding of
// methods/afn/fusion.h with no border test. Per pixel the operations are those of the portable
// kernel (normalised weights e_j / sum, taps summed in order j = 0..48) except the exponential's
// polynomial and the order of the sum of the exponentials: within the parity tolerance
// (AfnEngine.PortableAndAvx512KernelsAgree, AfnParity.*). Logits of heads that ran in bf16 take a
// cheaper exponential (exp16Bf16: 2^n p(f), a degree-4 polynomial, relative error 2.7e-6 against
// the 2e-7 of the Cephes one, where the logits themselves carry bf16's 4e-3): half its
// instructions. One pixel per call needs horizontal
// reductions for the maximum and the sums, which makes it several times slower
// (docs/performance.md).
#include "cpu/afn_filter_avx512.h"

#include "cpu/avx512.h"
#include "methods/afn/fusion.h"

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <limits>

namespace afn::cpu {

void PlanarRows::reset(const Image& img)
{
    m_img = &img;
    m_stride = img.width() + 2 * 3 + 16;
    const std::size_t size = static_cast<std::size_t>(8) * 3 * m_stride;
    if (m_buf.size() < size)
        m_buf.resize(size);
    for (int& row : m_slotRow)
        row = std::numeric_limits<int>::min();
}

void PlanarRows::ensure(int yy)
{
    int& slot = m_slotRow[yy & 7];
    if (slot == yy)
        return;
    slot = yy;
    float* base = m_buf.data() + static_cast<std::size_t>(yy & 7) * 3 * m_stride;
    const int w = m_img->width();
    if (yy < 0 || yy >= m_img->height()) {
        std::fill(base, base + 3 * m_stride, 0.0f);
        return;
    }
    const float* src = m_img->at(0, yy);
    for (int c = 0; c < 3; ++c) {
        float* p = base + c * m_stride;
        std::fill(p, p + 3, 0.0f);
        for (int x = 0; x < w; ++x)
            p[3 + x] = src[3 * x + c];
        std::fill(p + 3 + w, p + m_stride, 0.0f);
    }
}

const float* PlanarRows::plane(int yy, int c) const
{
    assert(m_slotRow[yy & 7] == yy);
    return m_buf.data() + (static_cast<std::size_t>(yy & 7) * 3 + c) * m_stride + 3;
}

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

/// exp(x) for x <= 0 where the logits come from bf16 heads: x log2(e) = n + f, n an integer,
/// |f| <= 1/2, then 2^f by a degree-4 polynomial (coefficients fitted for relative error on
/// [-1/2, 1/2]: at most 2.7e-6) scaled by 2^n (VSCALEFPS). x is clamped to -87 as in exp16: the
/// result stays a normal float, and -inf (a logit of -FLT_MAX against +FLT_MAX) gives no NaN.
AFN_CPU_AVX512_INLINE __m512 exp16Bf16(__m512 x)
{
    x = _mm512_max_ps(x, _mm512_set1_ps(-87.0f));
    const __m512 t = _mm512_mul_ps(x, _mm512_set1_ps(1.44269504088896341f));
    const __m512 n = _mm512_roundscale_ps(t, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    const __m512 f = _mm512_sub_ps(t, n);
    __m512 p = _mm512_set1_ps(0.00957007147371769f);
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(0.05591777339577675f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(0.240247443318367f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(0.6931218504905701f));
    p = _mm512_fmadd_ps(p, f, _mm512_set1_ps(0.9999992847442627f));
    return _mm512_scalef_ps(p, n);
}

/// v[j][i] = v[i][j] for a 16 x 16 block of floats (rows in, columns out): pairs unpacked within
/// 128-bit lanes, 64-bit halves shuffled, then the 4 x 4 transpose of the 128-bit lanes.
AFN_CPU_AVX512_INLINE void transpose16x16(__m512 (&v)[16])
{
    __m512 a[16], b[16];
    for (int k = 0; k < 8; ++k) {
        a[2 * k] = _mm512_unpacklo_ps(v[2 * k], v[2 * k + 1]);
        a[2 * k + 1] = _mm512_unpackhi_ps(v[2 * k], v[2 * k + 1]);
    }
    // b[4 k + q], 128-bit lane L: column 4 L + q of rows 4 k .. 4 k + 3.
    for (int k = 0; k < 4; ++k) {
        b[4 * k] = _mm512_shuffle_ps(a[4 * k], a[4 * k + 2], 0x44);
        b[4 * k + 1] = _mm512_shuffle_ps(a[4 * k], a[4 * k + 2], 0xEE);
        b[4 * k + 2] = _mm512_shuffle_ps(a[4 * k + 1], a[4 * k + 3], 0x44);
        b[4 * k + 3] = _mm512_shuffle_ps(a[4 * k + 1], a[4 * k + 3], 0xEE);
    }
    for (int q = 0; q < 4; ++q) {
        const __m512 d0 = _mm512_shuffle_f32x4(b[q], b[4 + q], 0x88);
        const __m512 d1 = _mm512_shuffle_f32x4(b[q], b[4 + q], 0xDD);
        const __m512 d2 = _mm512_shuffle_f32x4(b[8 + q], b[12 + q], 0x88);
        const __m512 d3 = _mm512_shuffle_f32x4(b[8 + q], b[12 + q], 0xDD);
        v[q] = _mm512_shuffle_f32x4(d0, d2, 0x88); // lane 0 of each
        v[8 + q] = _mm512_shuffle_f32x4(d0, d2, 0xDD); // lane 2
        v[4 + q] = _mm512_shuffle_f32x4(d1, d3, 0x88); // lane 1
        v[12 + q] = _mm512_shuffle_f32x4(d1, d3, 0xDD); // lane 3
    }
}

/// NaN -> -FLT_MAX, +-Inf -> +-FLT_MAX (max returns its second operand for a NaN first one).
AFN_CPU_AVX512_INLINE __m512 finite16(__m512 v)
{
    return _mm512_min_ps(_mm512_max_ps(v, _mm512_set1_ps(-FLT_MAX)), _mm512_set1_ps(FLT_MAX));
}

template <bool Bf16Logits>
AFN_CPU_AVX512_INLINE void softmaxApply(
    const float* logits, int stride, int n, const PlanarRows& rows, int x0, int y, float* rgb)
{
    const __mmask16 valid = firstLanes(n);
    const __m512i idx = _mm512_mullo_epi32(
        _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
        _mm512_set1_epi32(stride));
    const __m512 zero = _mm512_set1_ps(0.0f);
    // Taps j of the 16 pixels (the heads write each pixel's logits contiguously): taps 0-47 by
    // three 16 x 16 transposes of the pixels' logit rows (pixels past n read as zero, as the
    // gather's masked lanes), tap 48 by one gather. The maximum takes the taps in order j.
    alignas(64) float e[afnet::kKernelTaps][16];
    __m512 m = _mm512_set1_ps(-FLT_MAX);
    constexpr int kBlocks = afnet::kKernelTaps / 16;
    for (int b = 0; b < kBlocks; ++b) {
        __m512 v[16];
        for (int i = 0; i < 16; ++i)
            v[i] = _mm512_maskz_loadu_ps(static_cast<__mmask16>(i < n ? 0xFFFF : 0),
                logits + static_cast<long>(i) * stride + 16 * b);
        transpose16x16(v);
        for (int j = 0; j < 16; ++j) {
            const __m512 t = finite16(v[j]);
            _mm512_store_ps(e[16 * b + j], t);
            m = _mm512_max_ps(m, t);
        }
    }
    for (int j = 16 * kBlocks; j < afnet::kKernelTaps; ++j) {
        const __m512 v = finite16(_mm512_mask_i32gather_ps(zero, valid, idx, logits + j, 4));
        _mm512_store_ps(e[j], v);
        m = _mm512_max_ps(m, v);
    }
    __m512 s = zero;
    for (int j = 0; j < afnet::kKernelTaps; ++j) {
        const __m512 d = _mm512_sub_ps(_mm512_load_ps(e[j]), m);
        const __m512 v = Bf16Logits ? exp16Bf16(d) : exp16(d);
        _mm512_store_ps(e[j], v);
        s = _mm512_add_ps(s, v);
    }
    const __m512 inv = _mm512_div_ps(_mm512_set1_ps(1.0f), s);
    constexpr int r = afnet::kKernelSize / 2;
    __m512 acc[3] = { zero, zero, zero };
    for (int dy = 0; dy < afnet::kKernelSize; ++dy) {
        const float* p[3];
        for (int c = 0; c < 3; ++c)
            p[c] = rows.plane(y + dy - r, c) + x0 - r;
        for (int dx = 0; dx < afnet::kKernelSize; ++dx) {
            const __m512 wv = _mm512_mul_ps(_mm512_load_ps(e[dy * afnet::kKernelSize + dx]), inv);
            for (int c = 0; c < 3; ++c)
                acc[c] = _mm512_fmadd_ps(wv, _mm512_loadu_ps(p[c] + dx), acc[c]);
        }
    }
    alignas(64) float out[3][16];
    for (int c = 0; c < 3; ++c)
        _mm512_store_ps(out[c], acc[c]);
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            rgb[3 * i + c] = out[c][i];
}

} // namespace

AFN_CPU_AVX512 void softmaxApplyRowAvx512(const float* logits, int stride, int n,
    const PlanarRows& rows, int x0, int y, float* rgb, bool bf16Logits)
{
    if (bf16Logits)
        softmaxApply<true>(logits, stride, n, rows, x0, y, rgb);
    else
        softmaxApply<false>(logits, stride, n, rows, x0, y, rgb);
}

#else

void softmaxApplyRowAvx512(const float*, int, int, const PlanarRows&, int, int, float*, bool) { }

#endif

} // namespace afn::cpu
