// SPDX-License-Identifier: Apache-2.0
// SVGF's variance estimate, 8 pixels at a time (see methods/svgf/kernels.h; where the CPU has
// AVX-512 the 16-lane kernel of variance_avx512.cpp runs instead): the temporal variance
// max(0, m2 - m1^2) where the history is long enough, else the 7x7 cross-bilateral estimate of
// colour and moments (weights exp(-e) * max(0, n.n')^sigmaN, delta form around the centre) boosted
// by 4 / length (methods/svgf/denoiser.h); with VarianceArgs::spread, a first 7x7 pass with the
// guide's weights only gives each pixel's sparse share (kernels.h sparseShare), which scales its
// luminance term. A vector whose 8 pixels all have a long history skips
// the 7x7 loop. Weights of exp(-e) with e >= 87 (below 1.7e-38) are taken as 0: the scalar expf
// gave denormals there.
#include "cpu/isa.h"
#include "cpu/target.h"
#include "methods/svgf/kernels.h"
#include "methods/svgf/tap_vector.h"

#include <algorithm>
#include <cmath>

#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::svgf {

namespace {

constexpr float kExpFloor = 87.0f;

struct Estimate {
    V8 c[3], m[2];
};

/// The 7x7 cross-bilateral estimate of pixels x .. x + 7 of row y, with the luminance term
/// |l_p - l_q| / phi (per lane); kFull false: the guide's weights only, and no colour estimate
/// (the first pass of `spread` reads the moments; r.c is then the centre's colour).
template <bool kFull>
AFN_SVGF_INLINE Estimate crossBilateral(
    const VarianceArgs& a, int x, int y, const V8* cp, const V8* mp, V8 lp, V8 phi)
{
    const Planes& in = *a.in;
    const Guide& g = *a.guide;
    const int w = in.width(), h = in.height();
    const GuideCentre gc = guideCentre(g, x, y);
    V8 ws = {}, dc[3] = {}, dm[2] = {};
    for (int dy = -3; dy <= 3; ++dy) {
        const int qy = y + dy;
        if (qy < 0 || qy >= h)
            continue;
        for (int dx = -3; dx <= 3; ++dx) {
            const TapColumns t = tapColumns(x + dx, w);
            V8 e = {};
            if (kFull)
                e = absV(lp - loadTap(in.row(kIntLuminance, qy), t, w)) / phi;
            if (g.hasDepth)
                e = depthTerm(g, gc, loadTap(g.planes.row(kDepth, qy), t, w),
                        static_cast<float>(dx), static_cast<float>(dy))
                    + e;
            V8 wn = cpu::splat8(1.0f);
            if (g.hasNormal) {
                V8 nq[3];
                for (int k = 0; k < 3; ++k)
                    nq[k] = loadTap(g.planes.row(kNormalX + k, qy), t, w);
                wn = normalFactor(g, gc, nq);
            }
            const V8 ec = e < kExpFloor ? e : cpu::splat8(kExpFloor); // exp of masked-out lanes
            const V8 wq = (t.inImage & (e < kExpFloor)) ? cpu::exp8(-ec) * wn : V8 {};
            ws += wq;
            for (int k = 0; k < 3 && kFull; ++k)
                dc[k] += wq * (loadTap(in.row(kIntRed + k, qy), t, w) - cp[k]);
            for (int k = 0; k < 2; ++k)
                dm[k] += wq * (loadTap(in.row(kMoment1 + k, qy), t, w) - mp[k]);
        }
    }
    const V8 inv = ws > 0.0f ? 1.0f / ws : V8 {};
    Estimate r;
    for (int k = 0; k < 3; ++k)
        r.c[k] = cp[k] + dc[k] * inv;
    for (int k = 0; k < 2; ++k)
        r.m[k] = mp[k] + dm[k] * inv;
    return r;
}

} // namespace

/// varianceRows' body, always inlined into each clone: clang refuses 8-float vector calls in a
/// clone's own body for its baseline ("default") version, but not inside an always-inlined helper.
AFN_SVGF_INLINE void varianceRowsOf(const VarianceArgs& a, int y0, int y1)
{
    const FlushDenormals flush;
    const Planes& in = *a.in;
    Planes& out = *a.out;
    const int w = in.width();
    for (int y = y0; y < y1; ++y) {
        int xBegin, xEnd;
        regionColumns(a.region, y, w, xBegin, xEnd);
        for (int x = xBegin; x < xEnd; x += kLanes) {
            V8 c[3], m[2];
            for (int k = 0; k < 3; ++k)
                c[k] = cpu::load8(in.row(kIntRed + k, y) + x);
            for (int k = 0; k < 2; ++k)
                m[k] = cpu::load8(in.row(kMoment1 + k, y) + x);
            const V8 len = cpu::load8(in.row(kHistoryLength, y) + x);
            const V8 temporal = m[1] - m[0] * m[0];
            V8 var = temporal > 0.0f ? temporal : V8 {};
            // Tail lanes (x + l >= width) read length 0 from the padding: they count as short.
            const I8 shortHistory = len < a.varianceHistory;
            bool any = false;
            for (int l = 0; l < kLanes && x + l < w; ++l)
                any = any || shortHistory[l];
            if (any) {
                const V8 lp = cpu::load8(in.row(kIntLuminance, y) + x);
                V8 phi = cpu::splat8(a.phiL + 1e-10f);
                if (a.spread) {
                    const Estimate g = crossBilateral<false>(a, x, y, c, m, lp, phi);
                    const V8 var = g.m[1] - g.m[0] * g.m[0];
                    V8 sd = {};
                    for (int l = 0; l < kLanes; ++l)
                        sd[l] = std::sqrt(std::max(var[l], 0.0f));
                    const V8 cv = sd / (g.m[0] > 1e-20f ? g.m[0] : cpu::splat8(1e-20f));
                    for (int l = 0; l < kLanes; ++l)
                        phi[l] /= 1.0f - sparseShare(cv[l]); // 1 - 1 = 0: no luminance term
                }
                const Estimate e = crossBilateral<true>(a, x, y, c, m, lp, phi);
                const V8 spatial = e.m[1] - e.m[0] * e.m[0];
                const V8 boosted = (spatial > 0.0f ? spatial : V8 {}) * (4.0f / len);
                var = shortHistory ? boosted : var;
                for (int k = 0; k < 3; ++k)
                    c[k] = shortHistory ? e.c[k] : c[k];
            }
            for (int k = 0; k < 3; ++k)
                storeLanes(out.row(kRed + k, y), x, w, c[k]);
            storeLanes(out.row(kVariance, y), x, w, var);
            storeLanes(out.row(kLuminance, y), x, w, luminance8(c[0], c[1], c[2]));
        }
    }
}

AFN_CPU_KERNEL_CLONES void varianceRowsPortable(const VarianceArgs& a, int y0, int y1)
{
    varianceRowsOf(a, y0, y1);
}

void varianceRows(const VarianceArgs& a, int y0, int y1)
{
    if (cpu::activeIsa() == cpu::Isa::Avx512)
        varianceRowsAvx512(a, y0, y1);
    else
        varianceRowsPortable(a, y0, y1);
}

} // namespace afn::svgf
