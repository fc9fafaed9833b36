// SPDX-License-Identifier: Apache-2.0
// The post-filter's per-pixel luminance scale (post_filter_noise.h): a separable 5x5 box over the
// luminance and its square, along rows first (into a ring of 5 rows), then along columns, each
// row in a kernel cloned per instruction set. Compiled without FMA contraction (CMakeLists.txt):
// every clone gives the bits of the scalar formula.
#include "methods/afn/post_filter_noise.h"

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

std::size_t PostFilterNoiseRows::storageFloats(int w)
{
    // The ring's 2 r + 1 rows of means and of squares, then boxRowX's scratch.
    return static_cast<std::size_t>(w) * (2 * (2 * kRadius + 1) + 4) + 2 * kRadius;
}

PostFilterNoiseRows::PostFilterNoiseRows(
    const PostFilterNoiseInputs& in, int w, int h, float sigmaLuminance, float* storage)
    : m_irradiance(usable(in.irradiance, w, h, 3) ? in.irradiance : nullptr)
    , m_history(usable(in.historyLength, w, h, 1) ? in.historyLength : nullptr)
    , m_w(w)
    , m_h(h)
    , m_maxSamples(std::max(in.maxSamples, 1.0f))
    , m_base(0.5f * sigmaLuminance)
    , m_storage(storage)
{
}

float* PostFilterNoiseRows::boxMean(int y) const
{
    return m_storage + static_cast<std::size_t>(y % (2 * kRadius + 1)) * m_w;
}

float* PostFilterNoiseRows::boxSquare(int y) const
{
    return boxMean(y) + static_cast<std::size_t>(2 * kRadius + 1) * m_w;
}

void PostFilterNoiseRows::row(int y, float* scale)
{
    if (!m_irradiance) {
        std::fill(scale, scale + m_w, m_base);
        return;
    }
    // Rows: the box means of l and l^2 along x, of the rows y - r .. y + r not yet in the ring.
    if (m_nextBox < 0 || m_nextBox < y - kRadius) // the first row, or one past the ring's rows
        m_nextBox = std::max(0, y - kRadius);
    float* scratch = m_storage + static_cast<std::size_t>(2 * (2 * kRadius + 1)) * m_w;
    for (; m_nextBox <= std::min(y + kRadius, m_h - 1); ++m_nextBox)
        boxRowX(m_irradiance->at(0, m_nextBox), m_w, scratch, scratch + 3 * m_w, boxMean(m_nextBox),
            boxSquare(m_nextBox));
    // Columns: the 5x5 means, the relative noise of the accumulated estimate and the scale.
    const ScaleTerms t { m_history ? m_history->at(0, y) : nullptr, m_maxSamples,
        m_base / kPostFilterNoiseReference, m_base / kPostFilterNoiseClamp,
        m_base * kPostFilterNoiseClamp };
    const float* rows[2 * kRadius + 1][2];
    for (int dy = -kRadius; dy <= kRadius; ++dy) {
        const int q = std::clamp(y + dy, 0, m_h - 1);
        rows[dy + kRadius][0] = boxMean(q);
        rows[dy + kRadius][1] = boxSquare(q);
    }
    scaleRow(rows, m_w, t, scale);
}

} // namespace afn::afnet
