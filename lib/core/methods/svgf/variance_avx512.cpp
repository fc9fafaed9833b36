// SPDX-License-Identifier: Apache-2.0
// SVGF's variance estimate with AVX-512F, 16 pixels at a time (methods/svgf/kernels.h), used where
// cpu::activeIsa() is Avx512; the function carries its own target attribute. The formulas are the
// portable kernel's (variance_kernel.cpp): the temporal variance max(0, m2 - m1^2) where the
// history reaches varianceHistory, else the 7x7 cross-bilateral estimate of colour and moments
// (weights exp(-e) * max(0, n_p . n_q)^sigmaN, e = |l_p - l_q| / phiL + the depth term, delta form
// around the centre, weights of e >= 87 taken as 0) boosted by 4 / length. Computed with less
// work, as the à-trous kernel (atrous_avx512.cpp):
//   - the weight is one base-2 exponential, 2^-(log2e e), with 1 / phiL taken once per call;
//   - taps (dx, dy) and (-dx, -dy) share the depth term's denominator, so one division serves
//     both;
//   - 16 lanes, masked loads at the image's borders (lanes outside it get weight 0).
// With VarianceArgs::spread a first 7x7 pass with the guide's weights only gives each pixel's
// sparse share r (kernels.h sparseShare), and the luminance term's log2e / phiL is scaled by 1 - r
// (the same factor the portable kernel divides phiL by; r = 0 leaves every bit as without it).
// A vector whose 16 pixels all have a long history skips the 7x7 loop. The sums run in a fixed
// order per pixel (the centre, then the tap pairs): results do not depend on the row split, and
// differ from the portable kernel's in the last bits only
// (tests/unit/core/methods/svgf/test_svgf_variance_kernel.cpp checks both against a
// double-precision evaluation of the formulas).
#include "methods/svgf/avx512_math.h"
#include "methods/svgf/kernels.h"
#include "methods/svgf/tap_vector.h"

#include <algorithm>
#include <cmath>

namespace afn::svgf {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

constexpr float kExpFloor = 87.0f; ///< as variance_kernel.cpp: exp(-e), e >= 87, adds 0
constexpr int kRadius = 3;

/// The centre pixels' values, the guide's constants and the running sums.
struct Centre {
    __m512 c[3], m[2], l, n[3], z, dzdx, dzdy, zEps;
};
struct Sums {
    __m512 ws, dc[3], dm[2];
};

/// Add the tap at column qx of row qy (lanes `m` in the image) with the depth term's
/// log2e / denominator `rz` to the sums; kFull false: the guide's weights only, and no colour
/// sums (the first pass of `spread` reads the weights and moments).
template <bool kHasNormal, bool kHasDepth, int kSquarings, bool kFull = true>
AFN_CPU_AVX512_INLINE void addTap(const VarianceArgs& a, const NormalPower& np, const Centre& c,
    __m512 invPhi2, int qx, int qy, __mmask16 m, __m512 rz, Sums& s)
{
    const Planes& in = *a.in;
    const Guide& g = *a.guide;
    __m512 e2 = _mm512_setzero_ps();
    if (kFull) {
        const __m512 lq = _mm512_maskz_loadu_ps(m, in.row(kIntLuminance, qy) + qx);
        e2 = _mm512_mul_ps(absv(_mm512_sub_ps(c.l, lq)), invPhi2);
    }
    if (kHasDepth) {
        const __m512 zq = _mm512_maskz_loadu_ps(m, g.planes.row(kDepth, qy) + qx);
        e2 = _mm512_fmadd_ps(absv(_mm512_sub_ps(c.z, zq)), rz, e2);
    }
    // e < 87 <=> log2e e < 87 log2e; NaN fails the test, so it adds 0.
    const __mmask16 keep
        = _mm512_mask_cmp_ps_mask(m, e2, _mm512_set1_ps(kExpFloor * kLog2e), _CMP_LT_OQ);
    __m512 wq = exp2v(_mm512_sub_ps(_mm512_setzero_ps(), e2));
    if (kHasNormal) {
        __m512 d = _mm512_mul_ps(c.n[0], _mm512_maskz_loadu_ps(m, g.planes.row(kNormalX, qy) + qx));
        d = _mm512_fmadd_ps(c.n[1], _mm512_maskz_loadu_ps(m, g.planes.row(kNormalY, qy) + qx), d);
        d = _mm512_fmadd_ps(c.n[2], _mm512_maskz_loadu_ps(m, g.planes.row(kNormalZ, qy) + qx), d);
        wq = _mm512_mul_ps(wq, normalPower16<kSquarings>(np, d));
    }
    wq = _mm512_maskz_mov_ps(keep, wq);
    s.ws = _mm512_add_ps(s.ws, wq);
    for (int k = 0; k < 3 && kFull; ++k) {
        const __m512 cq = _mm512_maskz_loadu_ps(m, in.row(kIntRed + k, qy) + qx);
        s.dc[k] = _mm512_fmadd_ps(wq, _mm512_sub_ps(cq, c.c[k]), s.dc[k]);
    }
    for (int k = 0; k < 2; ++k) {
        const __m512 mq = _mm512_maskz_loadu_ps(m, in.row(kMoment1 + k, qy) + qx);
        s.dm[k] = _mm512_fmadd_ps(wq, _mm512_sub_ps(mq, c.m[k]), s.dm[k]);
    }
}

/// The 7x7 cross-bilateral sums of pixels x .. x + 15 of row y: the centre, then the 24 tap
/// pairs (dx, dy), (-dx, -dy) with dy > 0, or dy = 0 and dx > 0; the luminance term is
/// |l_p - l_q| invPhi2 (log2e / phiL per lane); kFull false: the guide's weights only, without
/// the colour sums (invPhi2 unread).
template <bool kHasNormal, bool kHasDepth, int kSquarings, bool kFull = true>
AFN_CPU_AVX512_INLINE Sums crossBilateral(
    const VarianceArgs& a, const NormalPower& np, const Centre& c, int x, int y, __m512 invPhi2)
{
    const int w = a.in->width(), h = a.in->height();
    const float sigmaZ = a.guide->sigmaZ;
    __mmask16 cols[2 * kRadius + 1];
    for (int dx = -kRadius; dx <= kRadius; ++dx)
        cols[dx + kRadius] = columnsInImage(x + dx, w);
    Sums s;
    s.ws = _mm512_setzero_ps();
    for (int k = 0; k < 3; ++k)
        s.dc[k] = _mm512_setzero_ps();
    for (int k = 0; k < 2; ++k)
        s.dm[k] = _mm512_setzero_ps();
    // The centre: e = 0 plus the depth term's 0; the normal factor of a unit normal with itself.
    addTap<kHasNormal, false, kSquarings, kFull>(
        a, np, c, invPhi2, x, y, cols[kRadius], _mm512_setzero_ps(), s);
    for (int dy = 0; dy <= kRadius; ++dy)
        for (int dx = dy == 0 ? 1 : -kRadius; dx <= kRadius; ++dx) {
            const bool up = y + dy < h, down = y - dy >= 0;
            if (!up && !down)
                continue;
            __m512 rz = _mm512_setzero_ps();
            if (kHasDepth) {
                // sigmaZ |dzdx dx + dzdy dy| + 1e-4 |z| + 1e-30: the same for (dx, dy) and
                // (-dx, -dy).
                const __m512 grad = _mm512_fmadd_ps(c.dzdx, _mm512_set1_ps(static_cast<float>(dx)),
                    _mm512_mul_ps(c.dzdy, _mm512_set1_ps(static_cast<float>(dy))));
                const __m512 denom = _mm512_fmadd_ps(_mm512_set1_ps(sigmaZ), absv(grad), c.zEps);
                rz = _mm512_div_ps(_mm512_set1_ps(kLog2e), denom);
            }
            if (up)
                addTap<kHasNormal, kHasDepth, kSquarings, kFull>(
                    a, np, c, invPhi2, x + dx, y + dy, cols[kRadius + dx], rz, s);
            if (down)
                addTap<kHasNormal, kHasDepth, kSquarings, kFull>(
                    a, np, c, invPhi2, x - dx, y - dy, cols[kRadius - dx], rz, s);
        }
    return s;
}

/// kernels.h sparseShare of 16 pixels from the sums of a pass with the guide's weights only.
AFN_CPU_AVX512_INLINE __m512 sparseShare16(const Sums& g, const Centre& c)
{
    const __m512 zero = _mm512_setzero_ps();
    const __mmask16 some = _mm512_cmp_ps_mask(g.ws, zero, _CMP_GT_OQ);
    const __m512 inv = _mm512_maskz_div_ps(some, _mm512_set1_ps(1.0f), g.ws);
    const __m512 m1 = _mm512_fmadd_ps(g.dm[0], inv, c.m[0]);
    const __m512 m2 = _mm512_fmadd_ps(g.dm[1], inv, c.m[1]);
    const __m512 sd = _mm512_sqrt_ps(_mm512_max_ps(_mm512_fnmadd_ps(m1, m1, m2), zero));
    const __m512 cv = _mm512_div_ps(sd, _mm512_max_ps(m1, _mm512_set1_ps(1e-20f)));
    const __m512 r = _mm512_mul_ps(_mm512_sub_ps(cv, _mm512_set1_ps(kSparseCvLow)),
        _mm512_set1_ps(1.0f / (kSparseCvHigh - kSparseCvLow)));
    // max first: a NaN r becomes 0, as sparseShare's.
    return _mm512_min_ps(_mm512_max_ps(r, zero), _mm512_set1_ps(1.0f));
}

template <bool kHasNormal, bool kHasDepth, int kSquarings>
AFN_CPU_AVX512 void varianceRows16(const VarianceArgs& a, int y0, int y1, const NormalPower& np)
{
    const Planes& in = *a.in;
    const Guide& g = *a.guide;
    Planes& out = *a.out;
    const int w = in.width();
    const __m512 zero = _mm512_setzero_ps();
    for (int y = y0; y < y1; ++y) {
        int xBegin, xEnd;
        regionColumns(a.region, y, w, xBegin, xEnd, 16);
        for (int x = xBegin; x < xEnd; x += 16) {
            const __mmask16 m0 = columnsInImage(x, w);
            Centre c;
            for (int k = 0; k < 3; ++k)
                c.c[k] = _mm512_maskz_loadu_ps(m0, in.row(kIntRed + k, y) + x);
            for (int k = 0; k < 2; ++k)
                c.m[k] = _mm512_maskz_loadu_ps(m0, in.row(kMoment1 + k, y) + x);
            const __m512 len = _mm512_maskz_loadu_ps(m0, in.row(kHistoryLength, y) + x);
            __m512 var = _mm512_max_ps(_mm512_fnmadd_ps(c.m[0], c.m[0], c.m[1]), zero);
            const __mmask16 shortHistory
                = _mm512_mask_cmp_ps_mask(m0, len, _mm512_set1_ps(a.varianceHistory), _CMP_LT_OQ);
            __m512 rgb[3] = { c.c[0], c.c[1], c.c[2] };
            if (shortHistory) {
                c.l = _mm512_maskz_loadu_ps(m0, in.row(kIntLuminance, y) + x);
                if (kHasNormal)
                    for (int k = 0; k < 3; ++k)
                        c.n[k] = _mm512_maskz_loadu_ps(m0, g.planes.row(kNormalX + k, y) + x);
                if (kHasDepth) {
                    c.z = _mm512_maskz_loadu_ps(m0, g.planes.row(kDepth, y) + x);
                    c.dzdx = _mm512_maskz_loadu_ps(m0, g.planes.row(kDepthDx, y) + x);
                    c.dzdy = _mm512_maskz_loadu_ps(m0, g.planes.row(kDepthDy, y) + x);
                    c.zEps = _mm512_add_ps(
                        _mm512_mul_ps(_mm512_set1_ps(1e-4f), absv(c.z)), _mm512_set1_ps(1e-30f));
                }
                __m512 invPhi2 = _mm512_set1_ps(kLog2e / (a.phiL + 1e-10f));
                if (a.spread)
                    invPhi2 = _mm512_mul_ps(invPhi2,
                        _mm512_sub_ps(_mm512_set1_ps(1.0f),
                            sparseShare16(crossBilateral<kHasNormal, kHasDepth, kSquarings, false>(
                                              a, np, c, x, y, zero),
                                c)));
                const Sums s
                    = crossBilateral<kHasNormal, kHasDepth, kSquarings>(a, np, c, x, y, invPhi2);
                const __mmask16 some = _mm512_cmp_ps_mask(s.ws, zero, _CMP_GT_OQ);
                const __m512 inv = _mm512_maskz_div_ps(some, _mm512_set1_ps(1.0f), s.ws);
                __m512 mo[2];
                for (int k = 0; k < 2; ++k)
                    mo[k] = _mm512_fmadd_ps(s.dm[k], inv, c.m[k]);
                const __m512 spatial = _mm512_max_ps(_mm512_fnmadd_ps(mo[0], mo[0], mo[1]), zero);
                const __m512 boosted
                    = _mm512_mul_ps(spatial, _mm512_div_ps(_mm512_set1_ps(4.0f), len));
                var = _mm512_mask_mov_ps(var, shortHistory, boosted);
                for (int k = 0; k < 3; ++k)
                    rgb[k] = _mm512_mask_mov_ps(
                        rgb[k], shortHistory, _mm512_fmadd_ps(s.dc[k], inv, c.c[k]));
            }
            for (int k = 0; k < 3; ++k)
                _mm512_mask_storeu_ps(out.row(kRed + k, y) + x, m0, rgb[k]);
            _mm512_mask_storeu_ps(out.row(kVariance, y) + x, m0, var);
            _mm512_mask_storeu_ps(
                out.row(kLuminance, y) + x, m0, luminance16(rgb[0], rgb[1], rgb[2]));
        }
    }
}

} // namespace

void varianceRowsAvx512(const VarianceArgs& a, int y0, int y1)
{
    const FlushDenormals flush;
    const NormalPower np = normalPowerOf(*a.guide);
    forGuide(*a.guide, [&](auto normal, auto depth, auto squarings) {
        varianceRows16<decltype(normal)::value, decltype(depth)::value, decltype(squarings)::value>(
            a, y0, y1, np);
    });
}

#else

void varianceRowsAvx512(const VarianceArgs& a, int y0, int y1)
{
    varianceRowsPortable(a, y0, y1);
}

#endif

} // namespace afn::svgf
