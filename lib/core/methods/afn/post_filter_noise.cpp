// SPDX-License-Identifier: Apache-2.0
// The post-filter's per-pixel luminance scale (post_filter_noise.h): a separable 5x5 box over the
// luminance and its square, rows first (into the two scratch planes), then columns.
#include "methods/afn/post_filter_noise.h"

#include "base/parallel.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace afn::afnet {

namespace {

bool usable(const Image* im, int w, int h, int channels)
{
    return im && im->width() == w && im->height() == h && im->channels() == channels;
}

/// Rec. 709 luminance of a pixel; non-finite channels count as 0.
float luminance(const float* c)
{
    auto finite = [](float v) { return std::fabs(v) <= FLT_MAX ? v : 0.0f; };
    return 0.2126f * finite(c[0]) + 0.7152f * finite(c[1]) + 0.0722f * finite(c[2]);
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
    const float maxSamples = std::max(in.maxSamples, 1.0f);
    constexpr int r = kPostFilterNoiseRadius;
    constexpr float inverseTaps = 1.0f / static_cast<float>(2 * r + 1);
    // Rows: the box means of l and l^2 along x.
    parallelRows(h, [&](int y0, int y1) {
        // One row's luminance with r border columns repeated on each side (so that the box's
        // loop has no clamp and vectorises), kept by each worker from frame to frame.
        thread_local std::vector<float> padded;
        padded.resize(static_cast<std::size_t>(w + 2 * r));
        for (int y = y0; y < y1; ++y) {
            const float* row = in.irradiance->at(0, y);
            float* l = padded.data() + r;
            for (int x = 0; x < w; ++x)
                l[x] = luminance(row + 3 * x);
            for (int k = 1; k <= r; ++k) {
                l[-k] = l[0];
                l[w - 1 + k] = l[w - 1];
            }
            float* mean = meanPlane + static_cast<std::size_t>(y) * w;
            float* square = squarePlane + static_cast<std::size_t>(y) * w;
            for (int x = 0; x < w; ++x) {
                float s1 = 0.0f, s2 = 0.0f;
                for (int dx = -r; dx <= r; ++dx) {
                    const float v = l[x + dx];
                    s1 += v;
                    s2 += v * v;
                }
                mean[x] = s1 * inverseTaps;
                square[x] = s2 * inverseTaps;
            }
        }
    });
    // Columns: the 5x5 means, the relative noise of the accumulated estimate and the scale.
    const float lo = base / kPostFilterNoiseClamp, hi = base * kPostFilterNoiseClamp;
    const float perReference = base / kPostFilterNoiseReference;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const float* rows[2 * r + 1][2];
            for (int dy = -r; dy <= r; ++dy) {
                const std::size_t o = static_cast<std::size_t>(std::clamp(y + dy, 0, h - 1)) * w;
                rows[dy + r][0] = meanPlane + o;
                rows[dy + r][1] = squarePlane + o;
            }
            const std::size_t o = static_cast<std::size_t>(y) * w;
            for (int x = 0; x < w; ++x) {
                float s1 = 0.0f, s2 = 0.0f;
                for (int k = 0; k < 2 * r + 1; ++k) {
                    s1 += rows[k][0][x];
                    s2 += rows[k][1][x];
                }
                const float mean = s1 * inverseTaps, variance = s2 * inverseTaps - mean * mean;
                float samples = history ? in.historyLength->data()[o + x] : 1.0f;
                samples = samples >= 1.0f ? std::min(samples, maxSamples) : 1.0f; // NaN too
                const float noise = std::sqrt(std::max(variance, 0.0f) / samples)
                    / (std::max(mean, 0.0f) + 1e-3f);
                const float s = noise * perReference;
                // NaN (inf - inf in the variance of overflowing luminance) takes the low end.
                scale[o + x] = s >= lo ? (s <= hi ? s : hi) : lo;
            }
        }
    });
}

} // namespace afn::afnet
