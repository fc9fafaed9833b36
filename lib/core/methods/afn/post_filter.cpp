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
#include <cstring>
#include <vector>

namespace afn::afnet {

namespace {

constexpr float kSpline[5] = { 1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f };
constexpr float kAlbedoScale = 1.0f / 0.1f; ///< da = sum |dA| / 0.1
constexpr float kDepthRelative = 0.02f; ///< dz's scale: 2 % of the depth per step

/// e^x for x <= 0 (x < -87 is taken as -87): 2^(x log2 e) split into an integer power, built in
/// the exponent bits, and a degree-6 Taylor polynomial of 2^f, f in [0, 1) (relative error
/// < 2e-5). Plain float code, so the loops that call it vectorise.
inline float expNonPositive(float x)
{
    x = x < -87.0f ? -87.0f : x;
    const float t = x * 1.44269504f;
    const float whole = std::floor(t);
    const float f = t - whole;
    float p = 1.540353e-4f;
    p = p * f + 1.333355e-3f;
    p = p * f + 9.618129e-3f;
    p = p * f + 5.550411e-2f;
    p = p * f + 2.402265e-1f;
    p = p * f + 6.931472e-1f;
    p = p * f + 1.0f;
    const std::int32_t bits = (static_cast<std::int32_t>(whole) + 127) << 23;
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

inline float finiteOr(float v, float fallback)
{
    return std::fabs(v) <= FLT_MAX ? v : fallback;
}

/// One tap's row: pointers to row y (p) and the tap's row qy (q) of the radiance and the guides
/// (guide pointers null when absent).
struct TapRows {
    const float* srcP;
    const float* srcQ;
    const float* albP;
    const float* albQ;
    const float* nrmP;
    const float* nrmQ;
    const float* depP;
    const float* depQ;
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
    const float* p = t.srcP + 3 * x;
    const float* q = t.srcQ + 3 * qx;
    const float lp = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    const float lq = 0.2126f * q[0] + 0.7152f * q[1] + 0.0722f * q[2];
    float e = std::fabs(lp - lq) / (kPostFilterSigmaLuminance * 0.5f * (lp + lq) + 1e-3f);
    if (t.albP) {
        const float* a = t.albP + 3 * x;
        const float* c = t.albQ + 3 * qx;
        const float da = std::fabs(finiteOr(a[0], 0.0f) - finiteOr(c[0], 0.0f))
            + std::fabs(finiteOr(a[1], 0.0f) - finiteOr(c[1], 0.0f))
            + std::fabs(finiteOr(a[2], 0.0f) - finiteOr(c[2], 0.0f));
        e += da * kAlbedoScale;
    }
    if (t.depP) {
        const float zp = finiteOr(t.depP[x], 1e30f), zq = finiteOr(t.depQ[qx], 1e30f);
        e += std::fabs(zp - zq) / (t.depthScale * std::max(zp, 1e-3f) + 1e-6f);
    }
    float w = t.splineWeight * expNonPositive(-e);
    if (t.nrmP) {
        const float* n = t.nrmP + 3 * x;
        const float* m = t.nrmQ + 3 * qx;
        const float nn = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
            * (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
        float d = (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]) / std::sqrt(std::max(nn, 1e-12f));
        d = d > 0.0f ? d : 0.0f;
        d *= d; // ^2
        d *= d; // ^4
        d *= d; // ^8
        d *= d; // ^16
        d *= d; // ^32
        d *= d; // ^64
        // Only where both normals are finite and not ~0 (a NaN or infinite one fails a compare).
        w *= (nn > 0.25f && nn <= FLT_MAX) ? d : 1.0f;
    }
    acc.r[x] += w * q[0];
    acc.g[x] += w * q[1];
    acc.b[x] += w * q[2];
    acc.w[x] += w;
}

/// The columns [x0, x1) whose tap, x + dx, is inside the row.
AFN_CPU_KERNEL_CLONES void addTapInterior(
    const TapRows& t, int x0, int x1, int dx, const RowAccumulators& acc)
{
    for (int x = x0; x < x1; ++x)
        addTap(t, x, x + dx, acc);
}

/// One a-trous pass with `step` from `src` into `dst`.
void filterPass(const Image& src, const PostFilterGuides& g, int step, Image& dst)
{
    const int w = src.width(), h = src.height();
    dst.resize(w, h, 3);
    auto usable = [&](const Image* im, int channels) {
        return im && im->width() == w && im->height() == h && im->channels() == channels;
    };
    const bool hasAlbedo = usable(g.albedo, 3);
    const bool hasNormal = usable(g.normal, 3);
    const bool hasDepth = usable(g.depth, 1);
    parallelRows(
        h,
        [&](int y0, int y1) {
            thread_local std::vector<float> buffer;
            buffer.assign(static_cast<std::size_t>(4) * w, 0.0f);
            const RowAccumulators acc { buffer.data(), buffer.data() + w, buffer.data() + 2 * w,
                buffer.data() + 3 * w };
            for (int y = y0; y < y1; ++y) {
                std::fill(buffer.begin(), buffer.end(), 0.0f);
                for (int i = -2; i <= 2; ++i) {
                    const int qy = std::clamp(y + i * step, 0, h - 1);
                    for (int j = -2; j <= 2; ++j) {
                        TapRows t {};
                        t.srcP = src.at(0, y);
                        t.srcQ = src.at(0, qy);
                        if (hasAlbedo) {
                            t.albP = g.albedo->at(0, y);
                            t.albQ = g.albedo->at(0, qy);
                        }
                        if (hasNormal) {
                            t.nrmP = g.normal->at(0, y);
                            t.nrmQ = g.normal->at(0, qy);
                        }
                        if (hasDepth) {
                            t.depP = g.depth->at(0, y);
                            t.depQ = g.depth->at(0, qy);
                        }
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

void edgeAwarePostFilter(
    const Image& radiance, const PostFilterGuides& guides, Image& scratch, Image& out)
{
    // Passes alternate between out and scratch so that the last one lands in out:
    // 3 passes: radiance -> out -> scratch -> out.
    const Image* src = &radiance;
    for (int k = 0; k < kPostFilterIterations; ++k) {
        Image& dst = (kPostFilterIterations - 1 - k) % 2 == 0 ? out : scratch;
        filterPass(*src, guides, 1 << k, dst);
        src = &dst;
    }
}

} // namespace afn::afnet
