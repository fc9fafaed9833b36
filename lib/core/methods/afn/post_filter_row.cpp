// SPDX-License-Identifier: Apache-2.0
// afn's post-filter's row kernel (post_filter_row.h). A row is filtered in runs of 16 pixels:
// the pixels' own guide values are loaded once, then the 4 outer taps are weighted and summed in
// registers, in the formula's order, and the run is normalised. Taps inside the image are
// contiguous loads; runs whose taps cross the left or right border read the clamped columns one
// by one. The depth term multiplies by the pixel's reciprocal of its scale (two per half-pass:
// rings 1 and 2) instead of dividing per tap.
#include "methods/afn/post_filter_row.h"

#include "cpu/target.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

// The vector helpers are always inlined into the one kernel (one target per clone): the vector
// ABI note does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::afnet {

namespace {

constexpr float kSpline[5] = { 1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f };
constexpr float kAlbedoScale = 1.0f / 0.1f; ///< da = sum |dA| / 0.1
constexpr float kDepthRelative = 0.02f; ///< dz's scale: 2 % of the depth per step

// 16 pixels of a row at a time (GCC/Clang vector extensions: one AVX-512 register in the
// x86-64-v4 clone, two AVX or four SSE registers in the others).

constexpr int kLanes = 16;
typedef float V __attribute__((vector_size(64)));
typedef float Vu __attribute__((vector_size(64), aligned(4))); ///< unaligned access
typedef std::int32_t I __attribute__((vector_size(64)));

#define AFN_PF_INLINE inline __attribute__((always_inline))

// No helper takes or returns a vector by value: the clones without AVX-512 would pass 64-byte
// vectors in another way than the AVX-512 one (Clang refuses such calls), so helpers write through
// references and the element-wise steps are written out.
#define AFN_PF_SPLAT(v) (V {} + (v))
#define AFN_PF_ABS(v) ((v) < 0.0f ? -(v) : (v))

AFN_PF_INLINE void loadV(V& out, const float* p)
{
    std::memcpy(&out, p, sizeof(V));
}

/// Below this exponent a tap's weight is 0: e^-40 is 3e-17 of the centre tap's weight, and the
/// products of smaller weights with dark colours are denormal floats, which cost the processor
/// about a hundred times a normal multiply (frames with sky or depth edges are full of them).
constexpr float kMinExponent = -40.0f;
/// Below this cosine the normal term is 0 (0.3^64 = 3e-34; smaller powers turn denormal).
constexpr float kMinNormalCosine = 0.3f;

/// e^x for x <= 0, 0 for x < kMinExponent and NaN: 2^(x log2 e) split into an integer power,
/// built in the exponent bits, and a degree-4 polynomial of 2^f, f in [0, 1) (least squares on
/// Chebyshev nodes; relative error < 3e-6). Per lane of a vector.
AFN_PF_INLINE void expNonPositiveV(V& inOut)
{
    const V xIn = inOut;
    const auto kept = xIn >= kMinExponent; // false for NaN
    const V x = kept ? xIn : AFN_PF_SPLAT(kMinExponent);
    const V t = x * 1.44269504f;
    const I whole = __builtin_convertvector(t, I) + (t < 0.0f); // (t < 0) is -1 where true
    const V f = t - __builtin_convertvector(whole, V);
    V p = AFN_PF_SPLAT(1.352060e-2f);
    p = p * f + 5.203743e-2f;
    p = p * f + 2.414275e-1f;
    p = p * f + 6.930066e-1f;
    p = p * f + 1.0000025f;
    const I bits = (whole + 127) << 23;
    V scale;
    std::memcpy(&scale, &bits, sizeof(scale));
    inOut = kept ? p * scale : AFN_PF_SPLAT(0.0f);
}

/// One plane's 16 values of row `row` at columns x0 + dx .. x0 + dx + 15, each clamped to
/// [0, w - 1] (taps beyond the border read the border column).
AFN_PF_INLINE void loadTap(V& out, const float* row, int x0, int dx, int w, bool interior)
{
    if (interior) {
        loadV(out, row + x0 + dx);
        return;
    }
    for (int k = 0; k < kLanes; ++k)
        out[k] = row[std::clamp(x0 + k + dx, 0, w - 1)];
}

/// The pixel's own guide values (loaded once for its taps).
struct Centre {
    V l, a0, a1, a2, n0, n1, n2, nv, ls;
    V z;
    V invDepth[2]; ///< 1 / (0.02 step ring max(z, 1e-3) + 1e-6) for rings 1 and 2
};

AFN_PF_INLINE void centrePlane(V& out, const float* v, std::size_t i, int n)
{
    if (n == kLanes) {
        loadV(out, v + i);
        return;
    }
    out = AFN_PF_SPLAT(0.0f);
    for (int k = 0; k < n; ++k)
        out[k] = v[i + static_cast<std::size_t>(k)];
}

/// Output pixels x0 .. x0 + n - 1 (n <= 16) of a row: the taps weighted and summed in their order,
/// normalised, written out. `Interior`: n is 16 and every tap's 16 columns lie inside the row
/// (contiguous loads); otherwise the clamped columns are read one by one.
template <bool Interior>
AFN_PF_INLINE void filterRun(const PostFilterRow& row, const PostFilterGuidePlanes& g, int w,
    int x0, int n, const PostFilterTap* taps, int step)
{
    const std::size_t c0 = static_cast<std::size_t>(x0), i0 = row.guideCentre + c0;
    Centre p;
    V r, gr, b;
    centrePlane(r, row.centre[0], c0, n), centrePlane(gr, row.centre[1], c0, n);
    centrePlane(b, row.centre[2], c0, n);
    p.l = 0.2126f * r + 0.7152f * gr + 0.0722f * b;
    centrePlane(p.a0, g.a0, i0, n), centrePlane(p.a1, g.a1, i0, n);
    centrePlane(p.a2, g.a2, i0, n);
    centrePlane(p.n0, g.n0, i0, n), centrePlane(p.n1, g.n1, i0, n);
    centrePlane(p.n2, g.n2, i0, n);
    centrePlane(p.nv, g.nv, i0, n);
    centrePlane(p.ls, g.ls, i0, n);
    centrePlane(p.z, g.z, i0, n);
    const V zmax = p.z > 1e-3f ? p.z : AFN_PF_SPLAT(1e-3f);
    for (int ring = 1; ring <= 2; ++ring)
        p.invDepth[ring - 1] = 1.0f
            / (kDepthRelative * static_cast<float>(step) * static_cast<float>(ring) * zmax + 1e-6f);
    // The centre tap first: its weight is h_2 exactly (no difference in luminance, albedo or
    // depth; a unit normal's cosine with itself is 1 to float rounding, whose 64th power is kept
    // out of the sum).
    V ar = kSpline[2] * r, ag = kSpline[2] * gr, ab = kSpline[2] * b, aw = AFN_PF_SPLAT(kSpline[2]);
    for (int k = 0; k < kPostFilterTaps; ++k) {
        const PostFilterTap& tap = taps[k];
        const std::size_t qrow = row.guideTap[k];
        const int dx = tap.dx;
        constexpr bool interior = Interior;
        V q0, q1, q2, t0, t1, t2, tz, tv;
        loadTap(q0, row.tap[k][0], x0, dx, w, interior);
        loadTap(q1, row.tap[k][1], x0, dx, w, interior);
        loadTap(q2, row.tap[k][2], x0, dx, w, interior);
        const V lq = 0.2126f * q0 + 0.7152f * q1 + 0.0722f * q2;
        const V sum = p.l + lq, diff = p.l - lq;
        V e = AFN_PF_ABS(diff) / (p.ls * (sum > 0.0f ? sum : AFN_PF_SPLAT(0.0f)) + 1e-3f);
        loadTap(t0, g.a0 + qrow, x0, dx, w, interior);
        loadTap(t1, g.a1 + qrow, x0, dx, w, interior);
        loadTap(t2, g.a2 + qrow, x0, dx, w, interior);
        t0 = p.a0 - t0, t1 = p.a1 - t1, t2 = p.a2 - t2;
        e += (AFN_PF_ABS(t0) + AFN_PF_ABS(t1) + AFN_PF_ABS(t2)) * kAlbedoScale;
        loadTap(tz, g.z + qrow, x0, dx, w, interior);
        tz = p.z - tz;
        e += AFN_PF_ABS(tz) * p.invDepth[tap.ring - 1];
        loadTap(t0, g.n0 + qrow, x0, dx, w, interior);
        loadTap(t1, g.n1 + qrow, x0, dx, w, interior);
        loadTap(t2, g.n2 + qrow, x0, dx, w, interior);
        V d = p.n0 * t0 + p.n1 * t1 + p.n2 * t2;
        d = d > kMinNormalCosine ? d : AFN_PF_SPLAT(0.0f);
        d *= d; // ^2
        d *= d; // ^4
        d *= d; // ^8
        d *= d; // ^16
        d *= d; // ^32
        d *= d; // ^64
        loadTap(tv, g.nv + qrow, x0, dx, w, interior);
        const V both = p.nv * tv; // 1 where both normals are valid, else 0
        V ex = -e;
        expNonPositiveV(ex);
        const V wt = tap.h * ex * (1.0f + both * (d - 1.0f));
        ar += wt * q0;
        ag += wt * q1;
        ab += wt * q2;
        aw += wt;
    }
    const V inv = 1.0f / aw; // >= the centre tap's weight h e^0 > 0
    ar *= inv, ag *= inv, ab *= inv;
    if (row.interleaved) {
        float* o = row.interleaved + 3 * c0;
        for (int k = 0; k < n; ++k) {
            o[3 * k] = ar[k];
            o[3 * k + 1] = ag[k];
            o[3 * k + 2] = ab[k];
        }
        return;
    }
    const std::size_t bytes = sizeof(float) * static_cast<std::size_t>(n);
    std::memcpy(row.out[0] + c0, &ar, bytes);
    std::memcpy(row.out[1] + c0, &ag, bytes);
    std::memcpy(row.out[2] + c0, &ab, bytes);
}

} // namespace

void postFilterTaps(bool horizontal, int step, PostFilterTap (&taps)[kPostFilterTaps])
{
    int count = 0;
    for (int j = -2; j <= 2; ++j)
        if (j != 0) // the centre tap is filterRun's own
            taps[count++] = { horizontal ? j * step : 0, horizontal ? 0 : j * step, kSpline[j + 2],
                std::abs(j) };
}

/// The runs whose taps all lie inside the row take the contiguous loads, the others (at most two
/// per side and the last, partial run) the clamped ones. One function per instruction-set clone,
/// the runs inlined into it.
AFN_CPU_KERNEL_CLONES void filterPostFilterRow(const PostFilterRow& row,
    const PostFilterGuidePlanes& g, int w, const PostFilterTap* taps, int step)
{
    int reach = 0; // the taps' largest |dx|
    for (int k = 0; k < kPostFilterTaps; ++k)
        reach = std::max(reach, std::abs(taps[k].dx));
    for (int x = 0; x < w; x += kLanes) {
        const int n = std::min(kLanes, w - x);
        if (n == kLanes && x - reach >= 0 && x + reach + kLanes <= w)
            filterRun<true>(row, g, w, x, n, taps, step);
        else
            filterRun<false>(row, g, w, x, n, taps, step);
    }
}

} // namespace afn::afnet
