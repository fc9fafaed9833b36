// SPDX-License-Identifier: Apache-2.0
// The gather's AVX-512F kernels (filter/gather_avx512.h); the functions carry their own target
// attribute.
// - gatherRunAvx512: the copy with the non-finite replacement and the per-value operation
//   (gatherValue), 16 values at a time; the counts are kept per lane and summed at the end.
// - normalizeNormals16: operation for operation the scalar code of filter/gather.cpp: p.z * zSign,
//   len = sqrt((x x + y y) + z z) without FMA, inv = 1 / len where len > 1e-12 (else 0), each
//   channel times inv (no FMA: compiled with -ffp-contract=off). The lengths are computed on the
//   channels taken apart; the products are done in the interleaved layout with inv spread to the 3
//   channels.
#include "filter/gather_avx512.h"
#include "cpu/avx512.h"
#include "cpu/avx512_rgb.h"

#include <algorithm>
#include <cstdint>

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// The constants and per-lane counts of one gatherRun.
struct RunState {
    __m512 rep, maxFinite, scaleEven, scaleOdd;
    __m512i bad, negative;
};

/// 16 values from i (m: the lanes in the run). `stream`: d + i is 64-byte aligned and m is full;
/// then a streaming store (the frame's buffers are read by later passes, not by this one: no read
/// of the destination lines for ownership). A run converted in place right after (normals, the
/// colour's demodulation) is stored normally: streamed, it would be read back from memory.
template <GatherOp::Kind K>
AFN_CPU_AVX512_INLINE void step(
    RunState& r, const float* s, float* d, int i, __mmask16 m, bool stream)
{
    const __m512 zero = _mm512_set1_ps(0.0f), one = _mm512_set1_ps(1.0f);
    const __m512i ones = _mm512_set1_epi32(1);
    __m512 v = _mm512_maskz_loadu_ps(m, s + i);
    const __mmask16 finite = _mm512_cmp_ps_mask(_mm512_abs_ps(v), r.maxFinite, _CMP_LE_OQ);
    r.bad = _mm512_mask_add_epi32(r.bad, static_cast<__mmask16>(m & ~finite), r.bad, ones);
    v = _mm512_mask_blend_ps(finite, r.rep, v);
    if constexpr (K == GatherOp::Kind::NonNegative) {
        const __mmask16 neg = _mm512_mask_cmp_ps_mask(m, v, zero, _CMP_LT_OQ);
        r.negative = _mm512_mask_add_epi32(r.negative, neg, r.negative, ones);
        v = _mm512_mask_mov_ps(v, neg, zero);
    } else if constexpr (K == GatherOp::Kind::Unit) {
        const __mmask16 below = _mm512_cmp_ps_mask(v, zero, _CMP_LT_OQ);
        const __mmask16 above = _mm512_cmp_ps_mask(v, one, _CMP_GT_OQ);
        v = _mm512_mask_mov_ps(_mm512_mask_mov_ps(v, below, zero), above, one);
    } else if constexpr (K == GatherOp::Kind::Scale2) {
        v = _mm512_mul_ps(v, (i & 1) ? r.scaleOdd : r.scaleEven);
    }
    if (stream)
        _mm512_stream_ps(d + i, v);
    else
        _mm512_mask_storeu_ps(d + i, m, v);
}

using cpu::firstLanes;

template <GatherOp::Kind K>
AFN_CPU_AVX512 void gatherRun(
    const float* s, float* d, int n, const GatherOp& op, GatherCounts& counts, bool stream)
{
    RunState r;
    r.rep = _mm512_set1_ps(op.replacement);
    r.maxFinite = _mm512_set1_ps(FLT_MAX);
    // Scale2: value i scales by sx for even i, sy for odd i (runs start at a pixel).
    const __m512 sx = _mm512_set1_ps(op.sx), sy = _mm512_set1_ps(op.sy);
    r.scaleEven = _mm512_mask_blend_ps(0xAAAA, sx, sy);
    r.scaleOdd = _mm512_mask_blend_ps(0xAAAA, sy, sx);
    r.bad = r.negative = _mm512_set1_epi32(0);
    // Up to 64-byte alignment of d with a masked step, then whole aligned vectors, then the tail.
    const int peel = std::min(n,
        static_cast<int>(((64 - (reinterpret_cast<std::uintptr_t>(d) & 63)) & 63) / sizeof(float)));
    int i = 0;
    if (peel > 0) {
        step<K>(r, s, d, 0, firstLanes(peel), false);
        i = peel;
    }
    if (stream)
        for (; i + 16 <= n; i += 16)
            step<K>(r, s, d, i, firstLanes(16), true);
    else
        for (; i + 16 <= n; i += 16)
            step<K>(r, s, d, i, firstLanes(16), false);
    if (i < n)
        step<K>(r, s, d, i, firstLanes(n - i), false);
    if (stream)
        _mm_sfence();
    counts.nonFinite += _mm512_reduce_add_epi32(r.bad);
    counts.negative += _mm512_reduce_add_epi32(r.negative);
}

} // namespace

void gatherRunAvx512(
    const float* s, float* d, int n, const GatherOp& op, GatherCounts& counts, bool stream)
{
    switch (op.kind) {
    case GatherOp::Kind::Copy:
        return gatherRun<GatherOp::Kind::Copy>(s, d, n, op, counts, stream);
    case GatherOp::Kind::NonNegative:
        return gatherRun<GatherOp::Kind::NonNegative>(s, d, n, op, counts, stream);
    case GatherOp::Kind::Unit:
        return gatherRun<GatherOp::Kind::Unit>(s, d, n, op, counts, stream);
    case GatherOp::Kind::Scale2:
        return gatherRun<GatherOp::Kind::Scale2>(s, d, n, op, counts, stream);
    }
}

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
        _mm512_storeu_ps(p + 16 * k, _mm512_mul_ps(v[k], cpu::spreadToPacked(inv, k)));
}

#else

void gatherRunAvx512(const float*, float*, int, const GatherOp&, GatherCounts&, bool) { }
void normalizeNormals16(float*, float) { }

#endif

} // namespace afn
