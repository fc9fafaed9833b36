// SPDX-License-Identifier: Apache-2.0
// The speckle test's first neighbour (stages/aux_noise.h), 16 pixels at a time with AVX-512F, used
// where cpu::activeIsa() is Avx512 (the function carries its own target attribute). On a clean
// buffer almost every pixel is within the threshold of its left neighbour, which the scalar test
// visits first and then stops: this pass decides those pixels, and the scalar test runs only on
// the others (from the start, so its answer is unchanged). The distances are the scalar ones
// operation for operation (absolute differences, maxima, one division; the normal's sum of
// squares in the same order, no FMA: compiled with -ffp-contract=off, see CMakeLists.txt), so the
// decision d <= t is the same bit for bit.
#include "cpu/avx512.h"
#include "cpu/avx512_rgb.h"
#include "stages/aux_noise_rows.h"

namespace afn {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

AFN_CPU_AVX512_INLINE __m512 absv(__m512 v)
{
    return _mm512_castsi512_ps(
        _mm512_and_si512(_mm512_castps_si512(v), _mm512_set1_epi32(0x7fffffff)));
}

} // namespace

AFN_CPU_AVX512 std::uint32_t leftNeighbourWithin16(const float* p, AuxKind kind, float t)
{
    __m512 a[3], q[3];
    for (int c = 0; c < 3; ++c) {
        a[c] = cpu::packedChannel(p, c);
        q[c] = cpu::packedChannel(p - 3, c);
    }
    __m512 d;
    __mmask16 ordered = 0xffff;
    if (kind == AuxKind::Albedo) {
        __m512 diff[3];
        for (int c = 0; c < 3; ++c) {
            diff[c] = absv(_mm512_sub_ps(a[c], q[c]));
            // A NaN difference makes the scalar distance NaN (std::max keeps it when first),
            // while vmaxps would drop it: such lanes are left to the scalar test.
            ordered = _mm512_mask_cmp_ps_mask(ordered, diff[c], diff[c], _CMP_ORD_Q);
        }
        d = _mm512_max_ps(_mm512_max_ps(diff[0], diff[1]), diff[2]);
        __m512 level = _mm512_set1_ps(kAuxAlbedoLevelFloor);
        for (int c = 0; c < 3; ++c)
            level = _mm512_max_ps(level, _mm512_max_ps(a[c], q[c]));
        d = _mm512_div_ps(d, level);
    } else {
        const __m512 dx = _mm512_sub_ps(a[0], q[0]), dy = _mm512_sub_ps(a[1], q[1]),
                     dz = _mm512_sub_ps(a[2], q[2]);
        const __m512 s = _mm512_add_ps(
            _mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)), _mm512_mul_ps(dz, dz));
        d = _mm512_sqrt_ps(s);
    }
    return _mm512_mask_cmp_ps_mask(ordered, d, _mm512_set1_ps(t), _CMP_LE_OQ);
}

AFN_CPU_AVX512 std::uint32_t depthSettled16(const float* p, float t)
{
    const __m512 z = _mm512_loadu_ps(p), q = _mm512_loadu_ps(p - 1);
    const __m512 sky = _mm512_set1_ps(kAuxDepthSky);
    // hasSurface: finite and |z| < 1e9 (NaN compares false, inf is not below 1e9).
    const __mmask16 surface = _mm512_cmp_ps_mask(absv(z), sky, _CMP_LT_OQ);
    const __mmask16 surfaceQ = _mm512_cmp_ps_mask(absv(q), sky, _CMP_LT_OQ);
    const __m512 az = absv(z), aq = absv(q);
    const __m512 d = _mm512_div_ps(
        absv(_mm512_sub_ps(z, q)), _mm512_max_ps(_mm512_min_ps(az, aq), _mm512_set1_ps(1e-6f)));
    const __mmask16 close = _mm512_mask_cmp_ps_mask(
        static_cast<__mmask16>(surface & surfaceQ), d, _mm512_set1_ps(t), _CMP_LE_OQ);
    return static_cast<std::uint32_t>(static_cast<__mmask16>(~surface) | close);
}

#else

std::uint32_t depthSettled16(const float*, float)
{
    return 0; // never called: activeIsa() is Portable without the AVX-512 kernels
}

std::uint32_t leftNeighbourWithin16(const float*, AuxKind, float)
{
    return 0; // never called: activeIsa() is Portable without the AVX-512 kernels
}

#endif

} // namespace afn
