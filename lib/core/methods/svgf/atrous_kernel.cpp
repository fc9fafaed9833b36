// SPDX-License-Identifier: Apache-2.0
// SVGF's à-trous iteration with its luminance scale invPhiL, 8 pixels at a time (see
// methods/svgf/kernels.h). The weights and sums are those of methods/svgf/denoiser.h, in the same
// order per pixel as the former scalar loop; taps whose weight is below exp(-40) or whose normal
// factor is 0 add exactly 0, as the scalar loop skipped them.
#include "cpu/target.h"
#include "methods/svgf/kernels.h"
#include "methods/svgf/tap_vector.h"

#include <algorithm>

#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::svgf {

namespace {

constexpr float kMaxExponent = 40.0f; ///< taps with exp(-e) below exp(-40) < 5e-18 are skipped
constexpr float kB3[3] = { 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f }; ///< by |offset|

/// invPhiL of pixels x .. x + 7 of row y (kernels.h AtrousArgs::sigmaL).
AFN_SVGF_INLINE V8 invPhi8(const Planes& in, float sigmaL, int x, int y)
{
    const int w = in.width(), h = in.height();
    // Out-of-image taps read the zero padding; the weight sum counts in-image taps only (a
    // product of per-axis sums: the weights are powers of two, so it is exact).
    V8 sum = {};
    float wy = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        const int qy = y + dy;
        if (qy < 0 || qy >= h)
            continue;
        const float ky = dy == 0 ? 0.5f : 0.25f;
        wy += ky;
        const float* v = in.row(kVariance, qy) + x;
        sum += (ky * 0.25f) * cpu::load8(v - 1);
        sum += (ky * 0.5f) * cpu::load8(v);
        sum += (ky * 0.25f) * cpu::load8(v + 1);
    }
    const I8 iota = { 0, 1, 2, 3, 4, 5, 6, 7 };
    const I8 px = iota + x;
    const V8 wx = cpu::splat8(1.0f) - ((px == 0) ? cpu::splat8(0.25f) : V8 {})
        - ((px == w - 1) ? cpu::splat8(0.25f) : V8 {});
    V8 blurred = sum / (wx * wy);
    blurred = blurred > 0.0f ? blurred : V8 {};
    V8 r = {};
    for (int l = 0; l < kLanes; ++l)
        r[l] = std::sqrt(blurred[l]);
    return 1.0f / (sigmaL * r + 1e-10f);
}

/// Running sums of one output vector.
struct Sums {
    V8 ws = {}, vsum = {}, dc[3] = {};
};

/// Add the taps of row qy (offset j) to the sums of pixels x .. x + 7 of row y; kHasNormal,
/// kHasDepth: the guide has that buffer.
template <bool kHasNormal, bool kHasDepth>
AFN_SVGF_INLINE void addTapRow(const AtrousArgs& a, const GuideCentre& gc, const V8* cp, V8 lp,
    V8 invPhi, int x, int qy, int j, Sums& s)
{
    const Planes& in = *a.in;
    const Guide& g = *a.guide;
    const int w = in.width(), step = a.step;
    const float* rows[kColorPlanes];
    for (int k = 0; k < kColorPlanes; ++k)
        rows[k] = in.row(k, qy);
    const float* zRow = kHasDepth ? g.planes.row(kDepth, qy) : nullptr;
    const float* nRows[3] = {};
    if (kHasNormal)
        for (int k = 0; k < 3; ++k)
            nRows[k] = g.planes.row(kNormalX + k, qy);
    for (int i = -2; i <= 2; ++i) {
        const TapColumns t = tapColumns(x + i * step, w);
        V8 cq[3];
        for (int k = 0; k < 3; ++k)
            cq[k] = loadTap(rows[k], t, w);
        const V8 vq = loadTap(rows[kVariance], t, w);
        const float h = kB3[std::abs(i)] * kB3[std::abs(j)];
        V8 wq;
        if (i == 0 && j == 0) {
            wq = cpu::splat8(h);
        } else {
            V8 e = absV(lp - loadTap(rows[kLuminance], t, w)) * invPhi;
            if (kHasDepth)
                e = depthTerm(g, gc, loadTap(zRow, t, w), static_cast<float>(i * step),
                        static_cast<float>(j * step))
                    + e;
            V8 wn = cpu::splat8(1.0f);
            if (kHasNormal) {
                V8 nq[3];
                for (int k = 0; k < 3; ++k)
                    nq[k] = loadTap(nRows[k], t, w);
                wn = normalFactor(g, gc, nq);
            }
            const I8 keep = t.inImage & (wn > 0.0f) & (e < kMaxExponent);
            // e clamped for the exp() of lanes that are masked out anyway.
            const V8 ec = e < kMaxExponent ? e : cpu::splat8(kMaxExponent);
            wq = keep ? h * (cpu::exp8(-ec) * wn) : V8 {};
        }
        s.ws += wq;
        s.vsum += wq * wq * vq;
        for (int k = 0; k < 3; ++k)
            s.dc[k] += wq * (cq[k] - cp[k]);
    }
}

template <bool kHasNormal, bool kHasDepth>
AFN_SVGF_INLINE void atrousRowsOf(const AtrousArgs& a, int y0, int y1)
{
    const Planes& in = *a.in;
    Planes& out = *a.out;
    const int w = in.width(), h = in.height();
    for (int v = y0; v < y1; ++v) {
        const int y = a.rowOrder ? a.rowOrder[v] : v;
        int xBegin, xEnd;
        regionColumns(a.region, y, w, xBegin, xEnd);
        xBegin = std::max(xBegin, a.x0);
        xEnd = std::min(xEnd, a.x1);
        for (int x = xBegin; x < xEnd; x += kLanes) {
            V8 cp[3];
            for (int k = 0; k < 3; ++k)
                cp[k] = cpu::load8(in.row(k, y) + x);
            const V8 lp = cpu::load8(in.row(kLuminance, y) + x);
            const V8 invPhi = invPhi8(in, a.sigmaL, x, y);
            const GuideCentre gc = guideCentre(*a.guide, x, y);
            Sums s;
            for (int j = -2; j <= 2; ++j) {
                const int qy = y + j * a.step;
                if (qy >= 0 && qy < h)
                    addTapRow<kHasNormal, kHasDepth>(a, gc, cp, lp, invPhi, x, qy, j, s);
            }
            const V8 inv = 1.0f / s.ws; // ws >= centre weight (3/8)^2 > 0 on in-image lanes
            V8 o[3];
            for (int k = 0; k < 3; ++k) {
                const V8 v = cp[k] + s.dc[k] * inv;
                o[k] = v > 0.0f ? v : V8 {}; // max(0, v), NaN -> 0
                storeLanes(out.row(k, y), x, w, o[k]);
            }
            storeLanes(out.row(kVariance, y), x, w, s.vsum * inv * inv);
            storeLanes(out.row(kLuminance, y), x, w, luminance8(o[0], o[1], o[2]));
        }
    }
}

} // namespace

AFN_CPU_KERNEL_CLONES void atrousRowsPortable(const AtrousArgs& a, int y0, int y1)
{
    const FlushDenormals flush;
    const Guide& g = *a.guide;
    if (g.hasNormal && g.hasDepth)
        atrousRowsOf<true, true>(a, y0, y1);
    else if (g.hasNormal)
        atrousRowsOf<true, false>(a, y0, y1);
    else if (g.hasDepth)
        atrousRowsOf<false, true>(a, y0, y1);
    else
        atrousRowsOf<false, false>(a, y0, y1);
}

} // namespace afn::svgf
