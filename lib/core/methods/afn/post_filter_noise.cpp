// SPDX-License-Identifier: Apache-2.0
// The post-filter's per-pixel luminance scale (post_filter_noise.h): a separable 5x5 box over the
// luminance and its square, rows first (into the two scratch planes), then columns, each row in a
// kernel cloned per instruction set. Compiled without FMA contraction (CMakeLists.txt): every
// clone gives the bits of the scalar formula.
#include "methods/afn/post_filter_noise.h"

#include "base/parallel.h"
#include "cpu/rgb_rows.h"
#include "cpu/target.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace afn::afnet {

namespace {

bool usable(const Image* im, int w, int h, int channels)
{
    return im && im->width() == w && im->height() == h && im->channels() == channels;
}

constexpr int kRadius = kPostFilterNoiseRadius;
constexpr float kInverseTaps = 1.0f / static_cast<float>(2 * kRadius + 1);

inline float finiteOrZero(float v)
{
    return std::fabs(v) <= FLT_MAX ? v : 0.0f;
}

/// Row y's box means of l and l^2 along x (l: Rec. 709 luminance, non-finite channels 0), with
/// `rgb` (3 w floats) and `padded` (w + 2 r floats) as the row's scratch: the colour split into
/// planes, then the luminance with r border columns repeated on each side, so that the loops
/// have no clamp and vectorise.
AFN_CPU_KERNEL_CLONES void boxRowX(
    const float* row, int w, float* rgb, float* padded, float* mean, float* square)
{
    float *r = rgb, *g = rgb + w, *b = rgb + 2 * w;
    cpu::deinterleaveRgbRow(row, r, g, b, w);
    float* l = padded + kRadius;
    for (int x = 0; x < w; ++x)
        l[x] = 0.2126f * finiteOrZero(r[x]) + 0.7152f * finiteOrZero(g[x])
            + 0.0722f * finiteOrZero(b[x]);
    for (int k = 1; k <= kRadius; ++k) {
        l[-k] = l[0];
        l[w - 1 + k] = l[w - 1];
    }
    for (int x = 0; x < w; ++x) {
        float s1 = 0.0f, s2 = 0.0f;
        for (int dx = -kRadius; dx <= kRadius; ++dx) {
            const float v = l[x + dx];
            s1 += v;
            s2 += v * v;
        }
        mean[x] = s1 * kInverseTaps;
        square[x] = s2 * kInverseTaps;
    }
}

/// What the column pass needs besides its rows.
struct ScaleTerms {
    const float* history; ///< the row's history lengths, or null (1 sample)
    float maxSamples, perReference, lo, hi;
};

/// Row y's scale from the box rows `rows[k]` (k = 0 .. 2 r: rows y - r .. y + r clamped; [0] the
/// means of l, [1] of l^2 along x).
AFN_CPU_KERNEL_CLONES void scaleRow(
    const float* const (&rows)[2 * kRadius + 1][2], int w, const ScaleTerms& t, float* scale)
{
    // Locals and restrict: the stores may not alias what the loop reads, so it vectorises.
    const float maxSamples = t.maxSamples, perReference = t.perReference, lo = t.lo, hi = t.hi;
    const float* __restrict history = t.history;
    float* __restrict out = scale;
    const float* __restrict m[2 * kRadius + 1];
    const float* __restrict q[2 * kRadius + 1];
    for (int k = 0; k < 2 * kRadius + 1; ++k)
        m[k] = rows[k][0], q[k] = rows[k][1];
    for (int x = 0; x < w; ++x) {
        float s1 = 0.0f, s2 = 0.0f;
        for (int k = 0; k < 2 * kRadius + 1; ++k) {
            s1 += m[k][x];
            s2 += q[k][x];
        }
        const float mean = s1 * kInverseTaps, variance = s2 * kInverseTaps - mean * mean;
        float samples = history ? history[x] : 1.0f;
        samples = samples >= 1.0f ? std::min(samples, maxSamples) : 1.0f; // NaN too
        const float noise
            = std::sqrt(std::max(variance, 0.0f) / samples) / (std::max(mean, 0.0f) + 1e-3f);
        const float s = noise * perReference;
        // NaN (inf - inf in the variance of overflowing luminance) takes the low end.
        out[x] = s >= lo ? (s <= hi ? s : hi) : lo;
    }
}

} // namespace

void postFilterLuminanceScale(const PostFilterNoiseInputs& in, int w, int h, float sigmaLuminance,
    float* meanPlane, float* squarePlane, float* scale)
{
    const std::size_t n = static_cast<std::size_t>(w) * h;
    const float base = 0.5f * sigmaLuminance;
    if (n == 0 || !usable(in.irradiance, w, h, 3)) {
        std::fill(scale, scale + n, base);
        return;
    }
    const bool history = usable(in.historyLength, w, h, 1);
    // Rows: the box means of l and l^2 along x.
    parallelRows(h, [&](int y0, int y1) {
        thread_local std::vector<float> scratch; // kept by each worker from frame to frame
        scratch.resize(static_cast<std::size_t>(4 * w + 2 * kRadius));
        for (int y = y0; y < y1; ++y) {
            const std::size_t o = static_cast<std::size_t>(y) * w;
            boxRowX(in.irradiance->at(0, y), w, scratch.data(), scratch.data() + 3 * w,
                meanPlane + o, squarePlane + o);
        }
    });
    // Columns: the 5x5 means, the relative noise of the accumulated estimate and the scale.
    ScaleTerms t { nullptr, std::max(in.maxSamples, 1.0f), base / kPostFilterNoiseReference,
        base / kPostFilterNoiseClamp, base * kPostFilterNoiseClamp };
    parallelRows(h, [&](int y0, int y1) {
        ScaleTerms rowTerms = t;
        for (int y = y0; y < y1; ++y) {
            const float* rows[2 * kRadius + 1][2];
            for (int dy = -kRadius; dy <= kRadius; ++dy) {
                const std::size_t o = static_cast<std::size_t>(std::clamp(y + dy, 0, h - 1)) * w;
                rows[dy + kRadius][0] = meanPlane + o;
                rows[dy + kRadius][1] = squarePlane + o;
            }
            const std::size_t o = static_cast<std::size_t>(y) * w;
            rowTerms.history = history ? in.historyLength->data() + o : nullptr;
            scaleRow(rows, w, rowTerms, scale + o);
        }
    });
}

} // namespace afn::afnet
