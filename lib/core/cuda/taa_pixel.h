// SPDX-License-Identifier: Apache-2.0
// afn's output TAA (stages/taa.h: the rule and its reasoning; methods/afn/settings.h: taa,
// taaAlpha) on the CUDA engine, one pixel at a time, in the CPU's order of operations (compiled
// with --fmad=false, taa.cu, as taa.cpp is compiled without contraction), so that the output is
// the CPU's bit for bit: the previous output sampled bilinearly over in-image taps at the
// reprojected position, clamped in YCoCg to the average of the 3x3 box and the 5-tap cross bounds
// of the current frame, blended with weight alpha, then pulled towards the current frame where the
// history trust is below 1 (TemporalAntialiasing::apply()).
#pragma once

#include "cuda/history_trust_block.h"
#include "cuda/temporal_pixel.h"

#include <cstddef>

namespace afn::cuda {

/// Buffers of the TAA (frame size, 3 floats per pixel).
struct TaaBuffers {
    int width = 0;
    int height = 0;
    const float* current = nullptr; ///< this frame's radiance
    const float* history = nullptr; ///< the previous frame's TAA output
    float* out = nullptr; ///< this frame's TAA output (the next frame's history)
};

namespace taa {

/// YCoCg component k of pixel (x, y) of `rgb` (taa.cpp yCoCgRow()).
AFN_HD float yCoCg(const float* rgb, int w, int x, int y, int k)
{
    const float* p = rgb + 3 * (static_cast<std::size_t>(y) * w + x);
    const float r = p[0], g = p[1], b = p[2];
    return k == 0 ? 0.25f * r + 0.5f * g + 0.25f * b
        : k == 1  ? 0.5f * r - 0.5f * b
                  : -0.25f * r + 0.5f * g - 0.25f * b;
}

AFN_HD float minF(float a, float b)
{
    return b < a ? b : a; // std::min
}
AFN_HD float maxF(float a, float b)
{
    return a < b ? b : a; // std::max
}

/// The 3-wide minimum and maximum of component k along row y at x (taa.cpp yCoCgRow()).
AFN_HD void rowBounds(const float* rgb, int w, int x, int y, int k, float& lo, float& hi)
{
    if (w == 1) {
        lo = hi = yCoCg(rgb, w, 0, y, k);
        return;
    }
    if (x == 0 || x == w - 1) {
        const int a = x == 0 ? 0 : w - 2;
        const float p0 = yCoCg(rgb, w, a, y, k), p1 = yCoCg(rgb, w, a + 1, y, k);
        lo = minF(p0, p1);
        hi = maxF(p0, p1);
        return;
    }
    const float pl = yCoCg(rgb, w, x - 1, y, k), pc = yCoCg(rgb, w, x, y, k);
    const float pr = yCoCg(rgb, w, x + 1, y, k);
    lo = minF(minF(pl, pc), pr);
    hi = maxF(maxF(pl, pc), pr);
}

/// max(0, blendHistory(h, c, alpha)).
AFN_HD float blendPositive(float h, float c, float alpha)
{
    float v = h + alpha * (c - h);
    v = fabsf(v) < 1.17549435e-38f ? 0.0f : v;
    return 0.0f < v ? v : 0.0f;
}

} // namespace taa

/// The TAA output of pixel (x, y): `taps` from the frame's reprojection (t, f), `trust` the
/// history trust when it was measured (else null); the history is read only where f.taaHistory.
AFN_HD void taaPixel(const TaaBuffers& a, const TemporalBuffers& t, const FrameConstants& f,
    const TrustBuffers* trust, int x, int y)
{
    using namespace taa;
    const int w = a.width, h = a.height;
    const std::size_t i = static_cast<std::size_t>(y) * w + x;
    const float* c = a.current + 3 * i;
    float* o = a.out + 3 * i;
    // The history: bilinear over in-image taps at the previous position (sampleHistory()).
    HistoryTaps taps;
    float hs[3] = { 0.0f, 0.0f, 0.0f };
    bool has = false;
    if (f.taaHistory && historyTaps(t, f, x, y, taps)) {
        float ws = 0.0f;
        for (int k = 0; k < 4; ++k) {
            const int qx = taps.x0 + (k & 1), qy = taps.y0 + (k >> 1);
            if (!(taps.bilinear[k] > 0.0f) || qx < 0 || qy < 0 || qx >= w || qy >= h)
                continue;
            const float* p = a.history + 3 * taps.index(w, k);
            for (int ch = 0; ch < 3; ++ch)
                hs[ch] += taps.bilinear[k] * p[ch];
            ws += taps.bilinear[k];
        }
        has = ws > 0.0f;
        if (has)
            for (int ch = 0; ch < 3; ++ch)
                hs[ch] /= ws;
        else
            hs[0] = hs[1] = hs[2] = 0.0f;
    }
    if (!has) {
        for (int ch = 0; ch < 3; ++ch)
            o[ch] = c[ch];
    } else {
        const int above = y > 0 ? y - 1 : 0, below = y + 1 < h ? y + 1 : h - 1;
        float lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            float aLo, aHi, cLo, cHi, bLo, bHi;
            rowBounds(a.current, w, x, above, k, aLo, aHi);
            rowBounds(a.current, w, x, y, k, cLo, cHi);
            rowBounds(a.current, w, x, below, k, bLo, bHi);
            const float aV = yCoCg(a.current, w, x, above, k);
            const float bV = yCoCg(a.current, w, x, below, k);
            const float boxLo = minF(minF(aLo, cLo), bLo), boxHi = maxF(maxF(aHi, cHi), bHi);
            const float crossLo = minF(minF(cLo, aV), bV), crossHi = maxF(maxF(cHi, aV), bV);
            lo[k] = 0.5f * (boxLo + crossLo);
            hi[k] = 0.5f * (boxHi + crossHi);
        }
        const float h0 = hs[0], h1 = hs[1], h2 = hs[2];
        const float hy[3] = { 0.25f * h0 + 0.5f * h1 + 0.25f * h2, 0.5f * h0 - 0.5f * h2,
            -0.25f * h0 + 0.5f * h1 - 0.25f * h2 };
        float q[3];
        bool outside = false;
        for (int k = 0; k < 3; ++k) {
            const bool under = hy[k]<lo[k], over = hy[k]> hi[k];
            outside = outside || under || over;
            q[k] = under ? lo[k] : (over ? hi[k] : hy[k]);
        }
        const float hist[3] = { outside ? q[0] + q[1] - q[2] : h0, outside ? q[0] + q[2] : h1,
            outside ? q[0] - q[1] - q[2] : h2 };
        for (int ch = 0; ch < 3; ++ch)
            o[ch] = blendPositive(hist[ch], c[ch], f.taaAlpha);
    }
    // The history trust pulls the output towards the current frame.
    if (trust && f.taaHistory) {
        const float tv = pixelTrust(*trust, x, y);
        if (tv < 1.0f)
            for (int ch = 0; ch < 3; ++ch)
                o[ch] = blendPositive(o[ch], c[ch], 1.0f - tv);
    }
}

} // namespace afn::cuda
