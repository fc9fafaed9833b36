// SPDX-License-Identifier: Apache-2.0
// BMFR's final temporal anti-aliasing (bmfr.cl taa), applied here to linear radiance (BMFR applies
// it after its gamma tone map; afn's output stays linear). History outside the clamp box is
// replaced by its YCoCg-clamped value; history inside is kept bit-exactly, so a static image is a
// fixed point.
#include "methods/bmfr/denoiser.h"

#include "base/parallel.h"

#include <algorithm>

namespace afn::bmfr {

namespace {

inline void toYCoCg(const float* c, float* o)
{
    o[0] = 0.25f * c[0] + 0.5f * c[1] + 0.25f * c[2];
    o[1] = 0.5f * c[0] - 0.5f * c[2];
    o[2] = -0.25f * c[0] + 0.5f * c[1] - 0.25f * c[2];
}

inline void fromYCoCg(const float* o, float* c)
{
    c[0] = o[0] + o[1] - o[2];
    c[1] = o[0] + o[2];
    c[2] = o[0] - o[1] - o[2];
}

/// Bilinear history at the reprojected position over in-image taps; false if none.
bool sampleHistory(const PixelTaps& t, const Image& history, float* out)
{
    if (!t.onScreen || t.box)
        return false;
    const float bw[4] = { (1.0f - t.fx) * (1.0f - t.fy), t.fx * (1.0f - t.fy), (1.0f - t.fx) * t.fy,
        t.fx * t.fy };
    float ws = 0.0f;
    out[0] = out[1] = out[2] = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const int x = t.x0 + (k & 1), y = t.y0 + (k >> 1);
        if (!(bw[k] > 0.0f) || x < 0 || y < 0 || x >= history.width() || y >= history.height())
            continue;
        const float* h = history.at(x, y);
        for (int c = 0; c < 3; ++c)
            out[c] += bw[k] * h[c];
        ws += bw[k];
    }
    if (!(ws > 0.0f))
        return false;
    for (int c = 0; c < 3; ++c)
        out[c] /= ws;
    return true;
}

} // namespace

void taa(const Reprojector& taps, const Image& cur, const Image& history, float alpha, Image& out)
{
    const int w = cur.width(), h = cur.height();
    out.resize(w, h, 3);
    const bool haveHistory = taps.hasHistory() && history.width() == w && history.height() == h;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* c = cur.at(x, y);
                float* o = out.at(x, y);
                float hist[3];
                if (!haveHistory || !sampleHistory(taps.taps(x, y), history, hist)) {
                    o[0] = c[0];
                    o[1] = c[1];
                    o[2] = c[2];
                    continue;
                }
                float boxLo[3], boxHi[3], crossLo[3], crossHi[3];
                for (int k = 0; k < 3; ++k) {
                    boxLo[k] = crossLo[k] = 3.4e38f;
                    boxHi[k] = crossHi[k] = -3.4e38f;
                }
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int qx = std::clamp(x + dx, 0, w - 1),
                                  qy = std::clamp(y + dy, 0, h - 1);
                        float q[3];
                        toYCoCg(cur.at(qx, qy), q);
                        const bool cross = dx == 0 || dy == 0;
                        for (int k = 0; k < 3; ++k) {
                            boxLo[k] = std::min(boxLo[k], q[k]);
                            boxHi[k] = std::max(boxHi[k], q[k]);
                            if (cross) {
                                crossLo[k] = std::min(crossLo[k], q[k]);
                                crossHi[k] = std::max(crossHi[k], q[k]);
                            }
                        }
                    }
                float hy[3];
                toYCoCg(hist, hy);
                bool inside = true;
                for (int k = 0; k < 3; ++k) {
                    const float lo = 0.5f * (boxLo[k] + crossLo[k]);
                    const float hi = 0.5f * (boxHi[k] + crossHi[k]);
                    if (hy[k] < lo || hy[k] > hi) {
                        inside = false;
                        hy[k] = std::clamp(hy[k], lo, hi);
                    }
                }
                if (!inside)
                    fromYCoCg(hy, hist);
                for (int k = 0; k < 3; ++k)
                    o[k] = std::max(0.0f, blendHistory(hist[k], c[k], alpha));
            }
    });
}

} // namespace afn::bmfr
