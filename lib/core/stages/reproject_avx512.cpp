// SPDX-License-Identifier: Apache-2.0
// The acceptance test of a static camera's rows (stages/reproject.h: identity rows, where each
// pixel tests only its own previous pixel), 16 pixels at a time with AVX-512F, used where
// cpu::activeIsa() is Avx512 (the function carries its own target attribute). It settles the
// usual cases, the previous position equal to the current one (then the normal test decides);
// a pixel whose position moved (the footprint test) or whose distance is NaN is left to the
// scalar test. The squared distances are the scalar ones operation for operation (differences,
// products, the sum in the same order, no FMA: compiled with -ffp-contract=off, see
// CMakeLists.txt), so the decisions are the same bit for bit.
#include "cpu/avx512.h"
#include "cpu/avx512_rgb.h"
#include "stages/reproject.h"
#include "stages/reproject_rows.h"

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// |a - b|^2 of 16 pixels, as the scalar dist2: (d0 d0 + d1 d1) + d2 d2.
AFN_CPU_AVX512_INLINE __m512 dist2(const float* a, const float* b)
{
    __m512 s = _mm512_setzero_ps();
    for (int c = 0; c < 3; ++c) {
        const __m512 d = _mm512_sub_ps(cpu::packedChannel(a, c), cpu::packedChannel(b, c));
        s = c == 0 ? _mm512_mul_ps(d, d) : _mm512_add_ps(s, _mm512_mul_ps(d, d));
    }
    return s;
}

/// Lanes whose 3 channels are all 0.
AFN_CPU_AVX512_INLINE __mmask16 zero3(const float* p)
{
    __mmask16 m = 0xffff;
    for (int c = 0; c < 3; ++c)
        m = _mm512_mask_cmp_ps_mask(m, cpu::packedChannel(p, c), _mm512_setzero_ps(), _CMP_EQ_OQ);
    return m;
}

} // namespace

AFN_CPU_AVX512 IdentityDecision identityTaps16(const IdentityRow16& r)
{
    // Position: equal positions pass; any other (moved, NaN) is left to the scalar test.
    const __mmask16 same
        = _mm512_cmp_ps_mask(dist2(r.prevPosition, r.position), _mm512_setzero_ps(), _CMP_EQ_OQ);
    __mmask16 pass = same;
    if (r.testNormal) {
        const __mmask16 zero = zero3(r.normal) | zero3(r.prevNormal);
        const __mmask16 close = _mm512_cmp_ps_mask(
            dist2(r.normal, r.prevNormal), _mm512_set1_ps(r.normalLimitSquared), _CMP_LT_OQ);
        pass = static_cast<__mmask16>(same & ~zero & close);
    }
    IdentityDecision d;
    d.accepted = pass;
    d.rejected = static_cast<std::uint32_t>(same & ~pass);
    return d;
}

AFN_CPU_AVX512 std::uint32_t Reprojector::ownPixelsAccepted16(int x, int y) const
{
    // TapBits is 4 bytes, little-endian: mask in the low 16 bits, box in bits 16-23; accepted
    // alone and not a box footprint: (bits & 0xFFFFFF) == 1, as ownPixelAccepted.
    static_assert(sizeof(TapBits) == 4);
    const __m512i b = _mm512_loadu_si512(&m_bits[static_cast<std::size_t>(y) * m_width + x]);
    return _mm512_cmpeq_epi32_mask(
        _mm512_and_si512(b, _mm512_set1_epi32(0xFFFFFF)), _mm512_set1_epi32(1));
}

AFN_CPU_AVX512 std::uint32_t Reprojector::storeIdentityBits16(
    TapBits* bits, std::uint32_t accepted, std::uint32_t rejected, bool boxFallback)
{
    // TapBits {mask, box, onScreen} as one little-endian 32-bit word: {1, 0, 1} = 0x01000001,
    // {0, 0, 1} = 0x01000000.
    static_assert(sizeof(TapBits) == 4);
    const std::uint32_t settled = accepted | (boxFallback ? 0u : rejected);
    const __m512i word = _mm512_mask_blend_epi32(static_cast<__mmask16>(accepted),
        _mm512_set1_epi32(0x01000000), _mm512_set1_epi32(0x01000001));
    _mm512_mask_storeu_epi32(bits, static_cast<__mmask16>(settled), word);
    return ~settled & 0xFFFFu;
}

#else

std::uint32_t Reprojector::ownPixelsAccepted16(int, int) const
{
    return 0; // never called: activeIsa() is Portable without the AVX-512 kernels
}

std::uint32_t Reprojector::storeIdentityBits16(TapBits*, std::uint32_t, std::uint32_t, bool)
{
    return 0xFFFFu; // never called: activeIsa() is Portable without the AVX-512 kernels
}

IdentityDecision identityTaps16(const IdentityRow16&)
{
    return {}; // never called: activeIsa() is Portable without the AVX-512 kernels
}

#endif

} // namespace afn
