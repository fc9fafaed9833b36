// SPDX-License-Identifier: Apache-2.0
// Noise-aware detail restoration after BMFR's regression (parameter "detail"; not in the paper).
//
// Why: BMFR's block fit (1, n, p, p^2 per 32x32 block) was made for 1 spp, where the accumulated
// colour is so noisy that whatever the fit cannot express is mostly noise. From 16 spp on the
// accumulated colour is close to clean and the fit's residual is mostly detail (texture of the
// lighting, contact shadows, glossy highlights): the published method then scores several dB
// below its own noisy input. So the residual r = accumulated - fit is kept in proportion to how
// much of it is signal, a Wiener shrinkage with the accumulated colour's noise variance:
//   fit' = fit + k r,   k = clamp(1 - var_acc / mean_3x3(lum(r)^2), 0, 1)
// var_acc per 8x8 block, from the current frame against the accumulation: with the accumulation's
// blend a (max(1 / len, alphaMin)) and history length h before this frame (capped at the effective
// sample count of the exponential average), current - accumulated = (1 - a)(n - m) has variance
// (1 - a)^2 s^2 (1 + 1 / h) for a frame noise variance s^2, and the accumulated colour's is
// s^2 ((1 - a)^2 / h + a^2). Pixels without history (len 1) do not count; a block with fewer than
// 8 that do takes half the mean squared difference of horizontal neighbours in the current frame
// (an upper bound of its noise: detail adds to it), and one whose estimate is not finite keeps
// the fit (k = 0). At 1 spp
// var_acc is large and k stays near 0 but at strong edges; at 16-64 spp most detail returns.
#include "methods/bmfr/detail.h"

#include "base/parallel.h"
#include "stages/history_trust.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace afn::bmfr {

namespace {

constexpr int kBlock = 8;
constexpr float kMinPixels = 8.0f;

/// The accumulated colour's noise variance in block (bx, by) (see the file comment); infinite
/// where it cannot be told.
float blockNoise(const Image& current, const Image& accumulated, const Image& length,
    float alphaMin, float effectiveLimit, int bx, int by)
{
    const int w = current.width(), h = current.height();
    double sum = 0.0, n = 0.0;
    for (int y = by * kBlock; y < std::min(h, (by + 1) * kBlock); ++y)
        for (int x = bx * kBlock; x < std::min(w, (bx + 1) * kBlock); ++x) {
            const double len = length(x, y, 0);
            const double a = std::max(1.0 / len, static_cast<double>(alphaMin));
            if (!(len > 1.0) || !(a < 1.0))
                continue;
            const double hist = std::min(len - 1.0, static_cast<double>(effectiveLimit));
            const double d
                = trustLuminance(current.at(x, y)) - trustLuminance(accumulated.at(x, y));
            const double frameVar = d * d / ((1.0 - a) * (1.0 - a) * (1.0 + 1.0 / hist));
            sum += frameVar * ((1.0 - a) * (1.0 - a) / hist + a * a);
            n += 1.0;
        }
    if (n < kMinPixels) { // no history to compare with: the frame's own pixel-to-pixel change
        sum = 0.0;
        n = 0.0;
        for (int y = by * kBlock; y < std::min(h, (by + 1) * kBlock); ++y)
            for (int x = bx * kBlock; x + 1 < std::min(w, (bx + 1) * kBlock); ++x) {
                const double d
                    = trustLuminance(current.at(x + 1, y)) - trustLuminance(current.at(x, y));
                sum += 0.5 * d * d; // var(a - b) = 2 s^2 where both are noise
                n += 1.0;
            }
    }
    const double v = sum / std::max(n, 1.0);
    return n >= kMinPixels && std::isfinite(v) ? static_cast<float>(v)
                                               : std::numeric_limits<float>::infinity();
}

} // namespace

void restoreDetail(const Image& accumulated, const Image& length, float alphaMin,
    float effectiveLimit, const Image& fit, Image& current)
{
    const int w = fit.width(), h = fit.height();
    const int bw = (w + kBlock - 1) / kBlock, bh = (h + kBlock - 1) / kBlock;
    std::vector<float> noise(static_cast<std::size_t>(bw) * bh);
    parallelRows(bh, [&](int by0, int by1) {
        for (int by = by0; by < by1; ++by)
            for (int bx = 0; bx < bw; ++bx)
                noise[static_cast<std::size_t>(by) * bw + bx]
                    = blockNoise(current, accumulated, length, alphaMin, effectiveLimit, bx, by);
    });
    // The residual's squared luminance of rows y - 1, y, y + 1 in a ring per band of rows (the
    // fit is read only), its 3x3 mean, and the result written over the current frame's colour
    // (read only by the block noise above).
    auto residualRow = [&](int y, float* out) {
        for (int x = 0; x < w; ++x) {
            const float* a = accumulated.at(x, y);
            const float* f = fit.at(x, y);
            const float r[3] = { a[0] - f[0], a[1] - f[1], a[2] - f[2] };
            const float l = trustLuminance(r);
            out[x] = l * l;
        }
    };
    parallelRows(h, [&](int y0, int y1) {
        thread_local std::vector<float> ring; // kept by each worker from frame to frame
        ring.resize(static_cast<std::size_t>(w) * 3);
        auto row = [&](int y) { return ring.data() + static_cast<std::size_t>(y % 3) * w; };
        for (int y = std::max(0, y0 - 1); y < std::min(h, y0 + 1); ++y)
            residualRow(y, row(y));
        for (int y = y0; y < y1; ++y) {
            if (y + 1 < h)
                residualRow(y + 1, row(y + 1));
            for (int x = 0; x < w; ++x) {
                const float* a = accumulated.at(x, y);
                const float* f = fit.at(x, y);
                float* o = current.at(x, y);
                const float var = noise[static_cast<std::size_t>(y / kBlock) * bw + x / kBlock];
                float k = 0.0f;
                if (std::isfinite(var)) {
                    float s = 0.0f;
                    int n = 0;
                    for (int qy = std::max(0, y - 1); qy <= std::min(h - 1, y + 1); ++qy)
                        for (int qx = std::max(0, x - 1); qx <= std::min(w - 1, x + 1); ++qx) {
                            s += row(qy)[qx];
                            ++n;
                        }
                    const float mean = s / static_cast<float>(n);
                    k = mean > var ? 1.0f - var / mean : 0.0f;
                }
                for (int c = 0; c < 3; ++c)
                    o[c] = k > 0.0f ? std::max(0.0f, f[c] + k * (a[c] - f[c])) : f[c];
            }
        }
    });
}

} // namespace afn::bmfr
