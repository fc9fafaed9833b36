// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (post_filter.h). Each pass works on runs of 16 pixels of a row: the
// pixels' own guide values are loaded once, then the 25 taps are weighted and summed in
// registers, in the formula's order, and the run is normalised. Taps inside the image are
// contiguous loads; runs whose taps cross the left or right border read the clamped columns one
// by one. The depth term multiplies by the pixel's reciprocal of its scale (two per pass: rings 1
// and 2) instead of dividing per tap.
#include "methods/afn/post_filter.h"

#include "base/parallel.h"
#include "cpu/target.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

// The vector helpers are always inlined into the one kernel (one target per clone): the vector
// ABI note does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::afnet {

namespace {

constexpr float kSpline[5] = { 1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f };
constexpr float kAlbedoScale = 1.0f / 0.1f; ///< da = sum |dA| / 0.1
constexpr float kDepthRelative = 0.02f; ///< dz's scale: 2 % of the depth per step

inline float finiteOr(float v, float fallback)
{
    return std::fabs(v) <= FLT_MAX ? v : fallback;
}

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
/// built in the exponent bits, and a degree-6 Taylor polynomial of 2^f, f in [0, 1) (relative
/// error < 2e-5). Per lane of a vector.
AFN_PF_INLINE void expNonPositiveV(V& inOut)
{
    const V xIn = inOut;
    const auto kept = xIn >= kMinExponent; // false for NaN
    const V x = kept ? xIn : AFN_PF_SPLAT(kMinExponent);
    const V t = x * 1.44269504f;
    const I whole = __builtin_convertvector(t, I) + (t < 0.0f); // (t < 0) is -1 where true
    const V f = t - __builtin_convertvector(whole, V);
    V p = AFN_PF_SPLAT(1.540353e-4f);
    p = p * f + 1.333355e-3f;
    p = p * f + 9.618129e-3f;
    p = p * f + 5.550411e-2f;
    p = p * f + 2.402265e-1f;
    p = p * f + 6.931472e-1f;
    p = p * f + 1.0f;
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

/// The pixel's own guide values (loaded once for its 25 taps).
struct Centre {
    V l, a0, a1, a2, n0, n1, n2, nv, ls;
    V z;
    V invDepth[2]; ///< 1 / (0.02 step ring max(z, 1e-3) + 1e-6) for rings 1 and 2
};

AFN_PF_INLINE void centrePlane(V& out, const std::vector<float>& v, std::size_t i, int n)
{
    if (n == kLanes) {
        loadV(out, v.data() + i);
        return;
    }
    out = AFN_PF_SPLAT(0.0f);
    for (int k = 0; k < n; ++k)
        out[k] = v[i + static_cast<std::size_t>(k)];
}

/// Output pixels x0 .. x0 + n - 1 (n <= 16) of row y: the 25 weighted taps summed in the order
/// (i, j) of the formula in post_filter.h, normalised, written interleaved to `out`.
AFN_CPU_KERNEL_CLONES void filterRun(const PostFilterColourPlanes& c,
    const PostFilterGuidePlanes& g, int w, int h, int y, int x0, int n, int step, float* out)
{
    const std::size_t i0 = static_cast<std::size_t>(y) * w + x0;
    Centre p;
    V r, gr, b;
    centrePlane(r, c.r, i0, n), centrePlane(gr, c.g, i0, n), centrePlane(b, c.b, i0, n);
    p.l = 0.2126f * r + 0.7152f * gr + 0.0722f * b;
    centrePlane(p.a0, g.a0, i0, n), centrePlane(p.a1, g.a1, i0, n), centrePlane(p.a2, g.a2, i0, n);
    centrePlane(p.n0, g.n0, i0, n), centrePlane(p.n1, g.n1, i0, n), centrePlane(p.n2, g.n2, i0, n);
    centrePlane(p.nv, g.nv, i0, n);
    centrePlane(p.ls, g.ls, i0, n);
    centrePlane(p.z, g.z, i0, n);
    const V zmax = p.z > 1e-3f ? p.z : AFN_PF_SPLAT(1e-3f);
    for (int ring = 1; ring <= 2; ++ring)
        p.invDepth[ring - 1] = 1.0f
            / (kDepthRelative * static_cast<float>(step) * static_cast<float>(ring) * zmax + 1e-6f);
    V ar = AFN_PF_SPLAT(0.0f), ag = ar, ab = ar, aw = ar;
    for (int i = -2; i <= 2; ++i) {
        const std::size_t qrow = static_cast<std::size_t>(std::clamp(y + i * step, 0, h - 1)) * w;
        for (int j = -2; j <= 2; ++j) {
            const int dx = j * step;
            const bool interior = n == kLanes && x0 + dx >= 0 && x0 + dx + kLanes <= w;
            V q0, q1, q2, t0, t1, t2, tz, tv;
            loadTap(q0, c.r.data() + qrow, x0, dx, w, interior);
            loadTap(q1, c.g.data() + qrow, x0, dx, w, interior);
            loadTap(q2, c.b.data() + qrow, x0, dx, w, interior);
            const V lq = 0.2126f * q0 + 0.7152f * q1 + 0.0722f * q2;
            const V sum = p.l + lq, diff = p.l - lq;
            V e = AFN_PF_ABS(diff) / (p.ls * (sum > 0.0f ? sum : AFN_PF_SPLAT(0.0f)) + 1e-3f);
            loadTap(t0, g.a0.data() + qrow, x0, dx, w, interior);
            loadTap(t1, g.a1.data() + qrow, x0, dx, w, interior);
            loadTap(t2, g.a2.data() + qrow, x0, dx, w, interior);
            t0 = p.a0 - t0, t1 = p.a1 - t1, t2 = p.a2 - t2;
            e += (AFN_PF_ABS(t0) + AFN_PF_ABS(t1) + AFN_PF_ABS(t2)) * kAlbedoScale;
            const int ring = std::max({ std::abs(i), std::abs(j), 1 });
            loadTap(tz, g.z.data() + qrow, x0, dx, w, interior);
            tz = p.z - tz;
            e += AFN_PF_ABS(tz) * p.invDepth[ring - 1];
            loadTap(t0, g.n0.data() + qrow, x0, dx, w, interior);
            loadTap(t1, g.n1.data() + qrow, x0, dx, w, interior);
            loadTap(t2, g.n2.data() + qrow, x0, dx, w, interior);
            V d = p.n0 * t0 + p.n1 * t1 + p.n2 * t2;
            d = d > kMinNormalCosine ? d : AFN_PF_SPLAT(0.0f);
            d *= d; // ^2
            d *= d; // ^4
            d *= d; // ^8
            d *= d; // ^16
            d *= d; // ^32
            d *= d; // ^64
            loadTap(tv, g.nv.data() + qrow, x0, dx, w, interior);
            const V both = p.nv * tv; // 1 where both normals are valid, else 0
            V ex = -e;
            expNonPositiveV(ex);
            const V wt = (kSpline[i + 2] * kSpline[j + 2]) * ex * (1.0f + both * (d - 1.0f));
            ar += wt * q0;
            ag += wt * q1;
            ab += wt * q2;
            aw += wt;
        }
    }
    const V inv = 1.0f / aw; // >= the centre tap's h_2^2 e^0 > 0
    ar *= inv, ag *= inv, ab *= inv;
    for (int k = 0; k < n; ++k) {
        out[3 * k] = ar[k];
        out[3 * k + 1] = ag[k];
        out[3 * k + 2] = ab[k];
    }
}

/// The guides as planes (PostFilterGuidePlanes, post_filter.h).
void buildGuidePlanes(const PostFilterGuides& g, int w, int h, PostFilterGuidePlanes& p)
{
    const std::size_t n = static_cast<std::size_t>(w) * h;
    auto usable = [&](const Image* im, int channels) {
        return im && im->width() == w && im->height() == h && im->channels() == channels;
    };
    for (auto* v : { &p.a0, &p.a1, &p.a2, &p.n0, &p.n1, &p.n2, &p.nv })
        v->assign(n, 0.0f);
    p.z.assign(n, 1.0f);
    const bool albedo = usable(g.albedo, 3), normal = usable(g.normal, 3),
               depth = usable(g.depth, 1);
    parallelRows(h, [&](int y0, int y1) {
        const std::size_t i0 = static_cast<std::size_t>(y0) * w;
        const std::size_t i1 = static_cast<std::size_t>(y1) * w;
        if (albedo)
            for (std::size_t i = i0; i < i1; ++i) {
                const float* a = g.albedo->data() + 3 * i;
                p.a0[i] = finiteOr(a[0], 0.0f);
                p.a1[i] = finiteOr(a[1], 0.0f);
                p.a2[i] = finiteOr(a[2], 0.0f);
            }
        if (normal)
            for (std::size_t i = i0; i < i1; ++i) {
                const float* m = g.normal->data() + 3 * i;
                const float len2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
                if (!(len2 > 0.5f && len2 <= FLT_MAX)) // ~0, NaN or infinite: no normal term
                    continue;
                const float inv = 1.0f / std::sqrt(len2);
                p.n0[i] = m[0] * inv;
                p.n1[i] = m[1] * inv;
                p.n2[i] = m[2] * inv;
                p.nv[i] = 1.0f;
            }
        if (depth)
            for (std::size_t i = i0; i < i1; ++i)
                p.z[i] = finiteOr(g.depth->data()[i], 1e30f);
    });
}

/// One a-trous pass with `step` from `src` into `dst` (3 ch); `planes` take `src`.
void filterPass(const Image& src, const PostFilterGuidePlanes& g, int step,
    PostFilterColourPlanes& planes, Image& dst)
{
    const int w = src.width(), h = src.height();
    const std::size_t n = static_cast<std::size_t>(w) * h;
    planes.r.resize(n);
    planes.g.resize(n);
    planes.b.resize(n);
    parallelRows(h, [&](int y0, int y1) {
        for (std::size_t i = static_cast<std::size_t>(y0) * w; i < static_cast<std::size_t>(y1) * w;
             ++i) {
            planes.r[i] = src.data()[3 * i];
            planes.g[i] = src.data()[3 * i + 1];
            planes.b[i] = src.data()[3 * i + 2];
        }
    });
    dst.resize(w, h, 3);
    parallelRows(
        h,
        [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < w; x += kLanes)
                    filterRun(planes, g, w, h, y, x, std::min(kLanes, w - x), step, dst.at(x, y));
        },
        4);
}

} // namespace

void edgeAwarePostFilter(const Image& radiance, const PostFilterGuides& guides,
    PostFilterWorkspace& workspace, Image& scratch, Image& out)
{
    // Passes alternate between out and scratch so that the last one lands in out:
    // 3 passes: radiance -> out -> scratch -> out.
    buildGuidePlanes(guides, radiance.width(), radiance.height(), workspace.guides);
    // The colour planes are free until the first pass fills them: the noise scale's scratch.
    postFilterLuminanceScale(guides.noise, radiance.width(), radiance.height(),
        kPostFilterSigmaLuminance, workspace.colour.r, workspace.colour.g, workspace.guides.ls);
    const Image* src = &radiance;
    for (int k = 0; k < kPostFilterIterations; ++k) {
        Image& dst = (kPostFilterIterations - 1 - k) % 2 == 0 ? out : scratch;
        filterPass(*src, workspace.guides, 1 << k, workspace.colour, dst);
        src = &dst;
    }
}

} // namespace afn::afnet
