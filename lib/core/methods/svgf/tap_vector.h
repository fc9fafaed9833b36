// SPDX-License-Identifier: Apache-2.0
// Helpers of SVGF's row kernels (methods/svgf/kernels.h): loading the 8 lanes of a tap, the guide
// terms of the edge-stopping weight (methods/svgf/guide.h). Included only by the kernel sources;
// always inlined, so they are compiled for the instruction set of the calling clone.
#pragma once

#include "cpu/simd.h"
#include "methods/svgf/guide.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

#define AFN_SVGF_INLINE inline __attribute__((always_inline))

namespace afn::svgf {

using cpu::I8;
using cpu::V8;

/// Flushes denormal results and inputs to zero (x86 MXCSR FTZ and DAZ) while it lives, restoring
/// the caller's mode after. Weights below FLT_MIN (exp(-e) of masked-out lanes, products of tiny
/// weights) would otherwise take microcode assists of ~100 cycles each; what they change is below
/// 1e-38 relative to the centre weight.
class FlushDenormals {
public:
#if defined(__x86_64__) || defined(__i386__)
    FlushDenormals()
        : m_saved(_mm_getcsr())
    {
        _mm_setcsr(m_saved | 0x8040u); // FTZ (bit 15) | DAZ (bit 6)
    }
    ~FlushDenormals()
    {
        _mm_setcsr(m_saved);
    }

private:
    unsigned m_saved;
#endif
};

/// Columns qx0 .. qx0 + 7 of a tap: whether they load directly, and which lie inside the image.
struct TapColumns {
    int qx0 = 0;
    bool direct = false; ///< inside the padded row: one unchecked load
    I8 inImage = {}; ///< -1 where 0 <= qx < width
};

AFN_SVGF_INLINE TapColumns tapColumns(int qx0, int width)
{
    const int rounded = (width + kLanes - 1) / kLanes * kLanes;
    TapColumns t;
    t.qx0 = qx0;
    t.direct = qx0 >= -kPlanePad && qx0 + kLanes <= rounded + kPlanePad;
    const I8 iota = { 0, 1, 2, 3, 4, 5, 6, 7 };
    const I8 q = iota + qx0;
    t.inImage = (q >= 0) & (q < width);
    return t;
}

/// The tap's 8 values of one row (lanes outside the image hold some in-image or padding value).
AFN_SVGF_INLINE V8 loadTap(const float* row, const TapColumns& t, int width)
{
    if (t.direct)
        return cpu::load8(row + t.qx0);
    V8 v;
    for (int l = 0; l < kLanes; ++l)
        v[l] = row[std::clamp(t.qx0 + l, 0, width - 1)];
    return v;
}

/// Store the in-image lanes of pixels x .. x + 7.
AFN_SVGF_INLINE void storeLanes(float* row, int x, int width, V8 v)
{
    if (x + kLanes <= width) {
        cpu::store8(row + x, v);
        return;
    }
    for (int l = 0; x + l < width; ++l)
        row[x + l] = v[l];
}

AFN_SVGF_INLINE V8 absV(V8 v)
{
    return v < 0.0f ? -v : v;
}

/// Guide values of the centre pixels p.
struct GuideCentre {
    V8 n[3]; ///< normal
    V8 z, dzdx, dzdy, zEps; ///< depth, its gradient, 1e-4 |z|
};

AFN_SVGF_INLINE GuideCentre guideCentre(const Guide& g, int x, int y)
{
    GuideCentre c {};
    if (g.hasNormal)
        for (int k = 0; k < 3; ++k)
            c.n[k] = cpu::load8(g.planes.row(kNormalX + k, y) + x);
    if (g.hasDepth) {
        c.z = cpu::load8(g.planes.row(kDepth, y) + x);
        c.dzdx = cpu::load8(g.planes.row(kDepthDx, y) + x);
        c.dzdy = cpu::load8(g.planes.row(kDepthDy, y) + x);
        c.zEps = 1e-4f * absV(c.z);
    }
    return c;
}

/// exp() argument of the depth term for taps at offset (dx, dy) with depth zq; 0 without depth.
AFN_SVGF_INLINE V8 depthTerm(const Guide& g, const GuideCentre& c, V8 zq, float dx, float dy)
{
    const V8 denom = g.sigmaZ * absV(c.dzdx * dx + c.dzdy * dy) + c.zEps + 1e-30f;
    return absV(c.z - zq) / denom;
}

/// max(0, n_p . n_q)^sigmaN; max(0, NaN) = 0 as std::fmax.
AFN_SVGF_INLINE V8 normalFactor(const Guide& g, const GuideCentre& c, const V8* nq)
{
    V8 d = c.n[0] * nq[0] + c.n[1] * nq[1] + c.n[2] * nq[2];
    d = d > 0.0f ? d : V8 {};
    if (!g.integerSigmaN) {
        V8 r;
        for (int l = 0; l < kLanes; ++l)
            r[l] = std::pow(d[l], g.sigmaN);
        return r;
    }
    unsigned e = static_cast<unsigned>(g.sigmaN);
    if (e != 0 && (e & (e - 1)) == 0) { // 2^k (the default 128): k squarings, no branch per bit
        for (; e > 1; e >>= 1u)
            d *= d;
        return d;
    }
    V8 result = cpu::splat8(1.0f), base = d;
    while (e) {
        if (e & 1u)
            result *= base;
        base *= base;
        e >>= 1u;
    }
    return result;
}

/// Rec. 709 luminance of 8 pixels (the same expression as luminance()).
AFN_SVGF_INLINE V8 luminance8(V8 r, V8 g, V8 b)
{
    return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

} // namespace afn::svgf

#pragma GCC diagnostic pop
