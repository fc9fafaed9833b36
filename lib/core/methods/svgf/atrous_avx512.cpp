// SPDX-License-Identifier: Apache-2.0
// SVGF's à-trous iteration with AVX-512F, 16 pixels at a time (methods/svgf/kernels.h), used where
// cpu::activeIsa() is Avx512; the function carries its own target attribute (the build has no
// -march). The same weights as the portable kernel (atrous_kernel.cpp), computed with less work:
//   - the weight is one base-2 exponential: w = 2^(log2 h - log2e (|l_p - l_q| invPhi + depth))
//     * max(0, n_p . n_q)^sigmaN, the B3 tap weight h folded into the exponent;
//     2^a = 2^floor(a) (vscalefps) * p(a - floor(a)), p a degree-5 minimax polynomial on [0, 1)
//     (relative error 1.6e-7 with FMA);
//   - taps q = p + o and p - o share the depth term's denominator sigmaZ |grad z . o| + 1e-4 |z|,
//     so one division serves both;
//   - masked loads (lanes outside the image read 0 without touching memory and get weight 0), so
//     any step is direct, and no tap needs a per-lane path; a block whose 24 taps all lie inside
//     the image (most blocks: cols all ones) loads them without masks, the same values and bits,
//     about 5 % faster on an AMD EPYC (docs/performance.md).
// Taps with exp(-e) below exp(-40) add exactly 0, as in the portable kernel. The sums run over the
// tap pairs in a fixed order per pixel: results do not depend on the thread count, and differ from
// the portable kernel's in the last bits only (tests/unit/core/methods/svgf/test_svgf_kernels.cpp
// checks both against a double-precision evaluation of the formulas).
#include "cpu/avx512.h"
#include "methods/svgf/avx512_math.h"
#include "methods/svgf/kernels.h"
#include "methods/svgf/tap_vector.h"

#include <algorithm>
#include <cmath>

namespace afn::svgf {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

constexpr float kMaxExponent = 40.0f; ///< as atrous_kernel.cpp: exp(-e) < exp(-40) adds 0
constexpr float kB3[3] = { 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f }; ///< by |offset|

/// The 16 values of a tap at p: lanes outside `m` read 0 without touching memory, or, in a block
/// whose taps all lie inside the image (kInterior, m all ones), one plain load.
template <bool kInterior> AFN_CPU_AVX512_INLINE __m512 loadTap(__mmask16 m, const float* p)
{
    return kInterior ? _mm512_loadu_ps(p) : _mm512_maskz_loadu_ps(m, p);
}

/// Row pointers of one tap row (ColorPlane order, then the guide's).
struct TapRow {
    const float* c[kColorPlanes];
    const float* n[3];
    const float* z;
};

/// The centre pixels' values and the running sums.
struct Centre {
    __m512 c[3], l, invPhi2, n[3], z, dzdx, dzdy, zEps;
};
struct Sums {
    __m512 ws, vsum, dc[3];
};

/// max(0, n_p . n_q)^sigmaN; kSquarings >= 0: sigmaN = 2^kSquarings (the default 128 = 2^7,
/// unrolled), -1: as `np` says.
template <bool kInterior, bool kHasNormal, int kSquarings>
AFN_CPU_AVX512_INLINE __m512 normalFactor16(
    const NormalPower& np, const Centre& c, const TapRow& r, int qx, __mmask16 m)
{
    if (!kHasNormal)
        return _mm512_set1_ps(1.0f);
    __m512 d = _mm512_mul_ps(c.n[0], loadTap<kInterior>(m, r.n[0] + qx));
    d = _mm512_fmadd_ps(c.n[1], loadTap<kInterior>(m, r.n[1] + qx), d);
    d = _mm512_fmadd_ps(c.n[2], loadTap<kInterior>(m, r.n[2] + qx), d);
    return normalPower16<kSquarings>(np, d);
}

/// Add the tap at column qx of row r (lanes `m` in the image), with log2 h = `log2h` and the
/// depth term's log2e / denominator `rz`, to the sums.
template <bool kInterior, bool kHasNormal, bool kHasDepth, int kSquarings>
AFN_CPU_AVX512_INLINE void addTap(const NormalPower& np, const Centre& c, const TapRow& r, int qx,
    __mmask16 m, float log2h, __m512 rz, Sums& s)
{
    const __m512 lq = loadTap<kInterior>(m, r.c[kLuminance] + qx);
    __m512 a = _mm512_fnmadd_ps(absv(_mm512_sub_ps(c.l, lq)), c.invPhi2, _mm512_set1_ps(log2h));
    if (kHasDepth) {
        const __m512 zq = loadTap<kInterior>(m, r.z + qx);
        a = _mm512_fnmadd_ps(absv(_mm512_sub_ps(c.z, zq)), rz, a);
    }
    // e < 40 <=> a > log2 h - 40 log2e; NaN fails the test, so it adds 0.
    const __mmask16 keep
        = _mm512_mask_cmp_ps_mask(m, a, _mm512_set1_ps(log2h - kMaxExponent * kLog2e), _CMP_GT_OQ);
    const __m512 wn = normalFactor16<kInterior, kHasNormal, kSquarings>(np, c, r, qx, m);
    const __m512 wq = _mm512_maskz_mul_ps(keep, exp2v(a), wn);
    s.ws = _mm512_add_ps(s.ws, wq);
    const __m512 vq = loadTap<kInterior>(m, r.c[kVariance] + qx);
    s.vsum = _mm512_fmadd_ps(_mm512_mul_ps(wq, wq), vq, s.vsum);
    for (int k = 0; k < 3; ++k) {
        const __m512 cq = loadTap<kInterior>(m, r.c[kRed + k] + qx);
        s.dc[k] = _mm512_fmadd_ps(wq, _mm512_sub_ps(cq, c.c[k]), s.dc[k]);
    }
}

/// The 12 tap pairs (i, j) and (-i, -j) of the 5x5 footprint without its centre: j > 0, or j = 0
/// and i > 0.
struct TapPair {
    int i, j;
};
constexpr TapPair kPairs[12] = { { 1, 0 }, { 2, 0 }, { -2, 1 }, { -1, 1 }, { 0, 1 }, { 1, 1 },
    { 2, 1 }, { -2, 2 }, { -1, 2 }, { 0, 2 }, { 1, 2 }, { 2, 2 } };

/// log2 of the B3 weight of offset (i, j).
constexpr float kLog2H[3][3] = { // by |j|, |i|
    { -2.830074998557688f, -3.415037499278844f, -5.415037499278844f },
    { -3.415037499278844f, -4.0f, -6.0f }, { -5.415037499278844f, -6.0f, -8.0f }
};

/// log2e * invPhiL of pixels x .. x + 15 of row y (kernels.h AtrousArgs::sigmaL), from the
/// variance of the rows y - 1, y, y + 1 (lanes outside the image load 0 and are not counted).
AFN_CPU_AVX512_INLINE __m512 invPhiLog2e(const Planes& in, float sigmaL, int x, int y, __mmask16 m0)
{
    const int w = in.width(), h = in.height();
    const __mmask16 left = columnsInImage(x - 1, w), right = columnsInImage(x + 1, w);
    __m512 sum = _mm512_setzero_ps();
    float wy = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        const int qy = y + dy;
        if (qy < 0 || qy >= h)
            continue;
        const float ky = dy == 0 ? 0.5f : 0.25f;
        wy += ky;
        const float* v = in.row(kVariance, qy) + x;
        sum = _mm512_fmadd_ps(_mm512_set1_ps(ky * 0.25f), _mm512_maskz_loadu_ps(left, v - 1), sum);
        sum = _mm512_fmadd_ps(_mm512_set1_ps(ky * 0.5f), _mm512_maskz_loadu_ps(m0, v), sum);
        sum = _mm512_fmadd_ps(_mm512_set1_ps(ky * 0.25f), _mm512_maskz_loadu_ps(right, v + 1), sum);
    }
    // In-image weight per lane: 1, less 1/4 at the first and at the last column.
    const __m512i px = _mm512_add_epi32(_mm512_set1_epi32(x),
        _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
    __m512 wx = _mm512_set1_ps(1.0f);
    wx = _mm512_mask_sub_ps(
        wx, _mm512_cmpeq_epi32_mask(px, _mm512_setzero_si512()), wx, _mm512_set1_ps(0.25f));
    wx = _mm512_mask_sub_ps(
        wx, _mm512_cmpeq_epi32_mask(px, _mm512_set1_epi32(w - 1)), wx, _mm512_set1_ps(0.25f));
    const __m512 blurred = _mm512_max_ps(
        _mm512_div_ps(sum, _mm512_mul_ps(wx, _mm512_set1_ps(wy))), _mm512_setzero_ps());
    const __m512 phi
        = _mm512_fmadd_ps(_mm512_set1_ps(sigmaL), _mm512_sqrt_ps(blurred), _mm512_set1_ps(1e-10f));
    return _mm512_div_ps(_mm512_set1_ps(kLog2e), phi);
}

// The tap loop is unrolled in optimised builds. Not under AddressSanitizer: there clang takes
// minutes to instrument the unrolled loop in every template instance (the CI's sanitizer build);
// the arithmetic and its order are the same either way.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define AFN_ATROUS_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(AFN_ATROUS_ASAN)
#define AFN_UNROLL_TAPS
#else
#define AFN_UNROLL_TAPS _Pragma("GCC unroll 12")
#endif

/// Sums of the 24 non-centre taps of pixels x .. x + 15 of the rows `rows` (offsets -2 .. 2);
/// kInterior: every tap's 16 columns lie inside the image (`cols` all ones).
template <bool kInterior, bool kHasNormal, bool kHasDepth, int kSquarings>
AFN_CPU_AVX512_INLINE void addTaps(const NormalPower& np, const Centre& c, const TapRow* rows,
    const bool* valid, const __mmask16* cols, int x, int step, float sigmaZ, Sums& s)
{
    AFN_UNROLL_TAPS
    for (int p = 0; p < 12; ++p) {
        const int i = kPairs[p].i, j = kPairs[p].j;
        const bool up = valid[2 + j], down = valid[2 - j];
        if (!up && !down)
            continue;
        const float l2h = kLog2H[j][i < 0 ? -i : i];
        __m512 rz = _mm512_setzero_ps();
        if (kHasDepth) {
            // sigmaZ |grad z . o| + 1e-4 |z|: the same for o and -o.
            const __m512 grad
                = _mm512_fmadd_ps(c.dzdx, _mm512_set1_ps(static_cast<float>(i * step)),
                    _mm512_mul_ps(c.dzdy, _mm512_set1_ps(static_cast<float>(j * step))));
            const __m512 denom = _mm512_fmadd_ps(_mm512_set1_ps(sigmaZ), absv(grad), c.zEps);
            rz = _mm512_div_ps(_mm512_set1_ps(kLog2e), denom);
        }
        if (up)
            addTap<kInterior, kHasNormal, kHasDepth, kSquarings>(
                np, c, rows[2 + j], x + i * step, cols[2 + i], l2h, rz, s);
        if (down)
            addTap<kInterior, kHasNormal, kHasDepth, kSquarings>(
                np, c, rows[2 - j], x - i * step, cols[2 - i], l2h, rz, s);
    }
}

template <bool kHasNormal, bool kHasDepth, int kSquarings>
AFN_CPU_AVX512 void atrousRows16(const AtrousArgs& a, int y0, int y1, const NormalPower& np)
{
    const Planes& in = *a.in;
    const Guide& g = *a.guide;
    Planes& out = *a.out;
    const int w = in.width(), h = in.height(), step = a.step;
    auto tapRow = [&](int qy) {
        TapRow r {};
        for (int k = 0; k < kColorPlanes; ++k)
            r.c[k] = in.row(k, qy);
        if (kHasNormal)
            for (int k = 0; k < 3; ++k)
                r.n[k] = g.planes.row(kNormalX + k, qy);
        if (kHasDepth)
            r.z = g.planes.row(kDepth, qy);
        return r;
    };
    for (int v = y0; v < y1; ++v) {
        const int y = a.rowOrder ? a.rowOrder[v] : v;
        int xBegin, xEnd; // work skipping: the row's span of AtrousArgs::region
        regionColumns(a.region, y, w, xBegin, xEnd, 16);
        xBegin = std::max(xBegin, a.x0);
        xEnd = std::min(xEnd, a.x1);
        if (xBegin >= xEnd)
            continue;
        TapRow rows[5];
        bool valid[5];
        for (int j = -2; j <= 2; ++j) {
            const int qy = y + j * step;
            valid[j + 2] = qy >= 0 && qy < h;
            if (valid[j + 2])
                rows[j + 2] = tapRow(qy);
        }
        for (int x = xBegin; x < xEnd; x += 16) {
            __mmask16 cols[5];
            for (int i = -2; i <= 2; ++i)
                cols[i + 2] = columnsInImage(x + i * step, w);
            const __mmask16 m0 = cols[2];
            const TapRow& centre = rows[2];
            Centre c;
            for (int k = 0; k < 3; ++k)
                c.c[k] = _mm512_maskz_loadu_ps(m0, centre.c[kRed + k] + x);
            c.l = _mm512_maskz_loadu_ps(m0, centre.c[kLuminance] + x);
            c.invPhi2 = invPhiLog2e(in, a.sigmaL, x, y, m0);
            if (kHasNormal)
                for (int k = 0; k < 3; ++k)
                    c.n[k] = _mm512_maskz_loadu_ps(m0, centre.n[k] + x);
            if (kHasDepth) {
                c.z = _mm512_maskz_loadu_ps(m0, centre.z + x);
                c.dzdx = _mm512_maskz_loadu_ps(m0, g.planes.row(kDepthDx, y) + x);
                c.dzdy = _mm512_maskz_loadu_ps(m0, g.planes.row(kDepthDy, y) + x);
                c.zEps = _mm512_add_ps(
                    _mm512_mul_ps(_mm512_set1_ps(1e-4f), absv(c.z)), _mm512_set1_ps(1e-30f));
            }
            const float hc = kB3[0] * kB3[0];
            Sums s;
            s.ws = _mm512_set1_ps(hc);
            s.vsum = _mm512_mul_ps(
                _mm512_set1_ps(hc * hc), _mm512_maskz_loadu_ps(m0, centre.c[kVariance] + x));
            for (int k = 0; k < 3; ++k)
                s.dc[k] = _mm512_setzero_ps();
            // Blocks whose taps all lie inside the image (most of them) load without masks:
            // the same values, so the same bits.
            bool interior = true;
            for (int i = 0; i < 5; ++i)
                interior = interior && cols[i] == 0xffff;
            if (interior)
                addTaps<true, kHasNormal, kHasDepth, kSquarings>(
                    np, c, rows, valid, cols, x, step, g.sigmaZ, s);
            else
                addTaps<false, kHasNormal, kHasDepth, kSquarings>(
                    np, c, rows, valid, cols, x, step, g.sigmaZ, s);
            const __m512 inv = _mm512_div_ps(_mm512_set1_ps(1.0f), s.ws);
            __m512 o[3];
            for (int k = 0; k < 3; ++k) {
                o[k] = _mm512_max_ps(_mm512_fmadd_ps(s.dc[k], inv, c.c[k]),
                    _mm512_setzero_ps()); // max(0, v), NaN -> 0
                _mm512_mask_storeu_ps(out.row(kRed + k, y) + x, m0, o[k]);
            }
            _mm512_mask_storeu_ps(
                out.row(kVariance, y) + x, m0, _mm512_mul_ps(_mm512_mul_ps(s.vsum, inv), inv));
            _mm512_mask_storeu_ps(out.row(kLuminance, y) + x, m0, luminance16(o[0], o[1], o[2]));
        }
    }
}

} // namespace

void atrousRowsAvx512(const AtrousArgs& a, int y0, int y1)
{
    const FlushDenormals flush;
    const Guide& g = *a.guide;
    const NormalPower np = normalPowerOf(g);
    forGuide(g, [&](auto normal, auto depth, auto squarings) {
        atrousRows16<decltype(normal)::value, decltype(depth)::value, decltype(squarings)::value>(
            a, y0, y1, np);
    });
}

#else

void atrousRowsAvx512(const AtrousArgs& a, int y0, int y1)
{
    atrousRowsPortable(a, y0, y1);
}

#endif

} // namespace afn::svgf
