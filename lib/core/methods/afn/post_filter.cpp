// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (post_filter.h). Each pass works row by row: for each of the 25
// taps it adds the tap's weighted colour into per-row accumulators, over the columns whose tap is
// inside the image in one vectorisable loop and over the few border columns (tap clamped to the
// first or last column) in a second one; the row is then normalised.
#include "methods/afn/post_filter.h"

#include "base/parallel.h"
#include "cpu/target.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <vector>

namespace afn::afnet {

namespace {

constexpr float kSpline[5] = { 1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f };
constexpr float kAlbedoScale = 1.0f / 0.1f; ///< da = sum |dA| / 0.1
constexpr float kDepthRelative = 0.02f; ///< dz's scale: 2 % of the depth per step

/// e^x for x <= 0 (x < -87 and NaN are taken as -87): 2^(x log2 e) split into an integer power,
/// built in the exponent bits, and a degree-6 Taylor polynomial of 2^f, f in [0, 1) (relative
/// error < 2e-5). Plain float code, so the loops that call it vectorise.
inline float expNonPositive(float x)
{
    x = x > -87.0f ? x : -87.0f; // also NaN (std::max would keep it)
    const float t = x * 1.44269504f;
    // floor(t) for t <= 0 (std::floor does not vectorise here): towards 0, minus 1 below 0 (an
    // integer t then gives f = 1, where the polynomial is 2 within its error).
    const std::int32_t whole = static_cast<std::int32_t>(t) - (t < 0.0f ? 1 : 0);
    const float f = t - static_cast<float>(whole);
    float p = 1.540353e-4f;
    p = p * f + 1.333355e-3f;
    p = p * f + 9.618129e-3f;
    p = p * f + 5.550411e-2f;
    p = p * f + 2.402265e-1f;
    p = p * f + 6.931472e-1f;
    p = p * f + 1.0f;
    const std::int32_t bits = (whole + 127) << 23;
    return p * __builtin_bit_cast(float, bits);
}

inline float finiteOr(float v, float fallback)
{
    return std::fabs(v) <= FLT_MAX ? v : fallback;
}

/// The planes' rows: p = the pixel's row y, q = the tap's row qy.
struct TapRows {
    const float *rP, *gP, *bP, *rQ, *gQ, *bQ;
    const float *a0P, *a1P, *a2P, *a0Q, *a1Q, *a2Q;
    const float *n0P, *n1P, *n2P, *nvP, *n0Q, *n1Q, *n2Q, *nvQ;
    const float *zP, *zQ;
    const float* lsP; ///< the luminance term's scale s_p
    float splineWeight; ///< h_i h_j
    float depthScale; ///< 0.02 * step * max(|i|, |j|, 1)
};

struct RowAccumulators {
    float* r;
    float* g;
    float* b;
    float* w;
};

/// Pixel x of the row and its tap at column qx: the tap's weight and colour added in.
inline void addTap(const TapRows& t, int x, int qx, const RowAccumulators& acc)
{
    const float q0 = t.rQ[qx], q1 = t.gQ[qx], q2 = t.bQ[qx];
    const float lp = 0.2126f * t.rP[x] + 0.7152f * t.gP[x] + 0.0722f * t.bP[x];
    const float lq = 0.2126f * q0 + 0.7152f * q1 + 0.0722f * q2;
    float e = std::fabs(lp - lq) / (t.lsP[x] * std::max(lp + lq, 0.0f) + 1e-3f);
    e += (std::fabs(t.a0P[x] - t.a0Q[qx]) + std::fabs(t.a1P[x] - t.a1Q[qx])
             + std::fabs(t.a2P[x] - t.a2Q[qx]))
        * kAlbedoScale;
    const float zp = t.zP[x];
    e += std::fabs(zp - t.zQ[qx]) / (t.depthScale * std::max(zp, 1e-3f) + 1e-6f);
    float d = t.n0P[x] * t.n0Q[qx] + t.n1P[x] * t.n1Q[qx] + t.n2P[x] * t.n2Q[qx];
    d = std::max(d, 0.0f);
    d *= d; // ^2
    d *= d; // ^4
    d *= d; // ^8
    d *= d; // ^16
    d *= d; // ^32
    d *= d; // ^64
    const float both = t.nvP[x] * t.nvQ[qx]; // 1 where both normals are valid, else 0
    const float w = t.splineWeight * expNonPositive(-e) * (1.0f + both * (d - 1.0f));
    acc.r[x] += w * q0;
    acc.g[x] += w * q1;
    acc.b[x] += w * q2;
    acc.w[x] += w;
}

/// The columns [x0, x1), whose tap x + dx is inside the row: contiguous planes, so it vectorises.
AFN_CPU_KERNEL_CLONES void addTapInterior(
    const TapRows& t, int x0, int x1, int dx, const RowAccumulators& acc)
{
    // The accumulators are the filter's own rows, apart from every plane read (GCC would need
    // more run-time alias checks than it makes).
#pragma GCC ivdep
    for (int x = x0; x < x1; ++x)
        addTap(t, x, x + dx, acc);
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
            thread_local std::vector<float> buffer;
            buffer.assign(static_cast<std::size_t>(4) * w, 0.0f);
            const RowAccumulators acc { buffer.data(), buffer.data() + w, buffer.data() + 2 * w,
                buffer.data() + 3 * w };
            auto row = [&](const std::vector<float>& v, int y) {
                return v.data() + static_cast<std::size_t>(y) * w;
            };
            for (int y = y0; y < y1; ++y) {
                std::fill(buffer.begin(), buffer.end(), 0.0f);
                for (int i = -2; i <= 2; ++i) {
                    const int qy = std::clamp(y + i * step, 0, h - 1);
                    TapRows t {};
                    t.rP = row(planes.r, y), t.gP = row(planes.g, y), t.bP = row(planes.b, y);
                    t.rQ = row(planes.r, qy), t.gQ = row(planes.g, qy), t.bQ = row(planes.b, qy);
                    t.a0P = row(g.a0, y), t.a1P = row(g.a1, y), t.a2P = row(g.a2, y);
                    t.a0Q = row(g.a0, qy), t.a1Q = row(g.a1, qy), t.a2Q = row(g.a2, qy);
                    t.n0P = row(g.n0, y), t.n1P = row(g.n1, y), t.n2P = row(g.n2, y);
                    t.nvP = row(g.nv, y);
                    t.n0Q = row(g.n0, qy), t.n1Q = row(g.n1, qy), t.n2Q = row(g.n2, qy);
                    t.nvQ = row(g.nv, qy);
                    t.zP = row(g.z, y), t.zQ = row(g.z, qy);
                    t.lsP = row(g.ls, y);
                    for (int j = -2; j <= 2; ++j) {
                        t.splineWeight = kSpline[i + 2] * kSpline[j + 2];
                        t.depthScale = kDepthRelative * static_cast<float>(step)
                            * static_cast<float>(std::max({ std::abs(i), std::abs(j), 1 }));
                        const int dx = j * step;
                        const int x0 = std::clamp(-dx, 0, w), x1 = std::clamp(w - dx, x0, w);
                        addTapInterior(t, x0, x1, dx, acc);
                        for (int x = 0; x < x0; ++x)
                            addTap(t, x, 0, acc);
                        for (int x = x1; x < w; ++x)
                            addTap(t, x, w - 1, acc);
                    }
                }
                float* out = dst.at(0, y);
                for (int x = 0; x < w; ++x) {
                    const float inv = 1.0f / acc.w[x]; // >= the centre tap's h_2^2 e^0 > 0
                    out[3 * x] = acc.r[x] * inv;
                    out[3 * x + 1] = acc.g[x] * inv;
                    out[3 * x + 2] = acc.b[x] * inv;
                }
            }
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
