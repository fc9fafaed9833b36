// SPDX-License-Identifier: Apache-2.0
// The history trust (stages/history_trust.h: the rule, its constants and its reasoning) on the
// CUDA engine, in the CPU's order of operations so that the trust, and so the temporal
// accumulation, are the CPU's bit for bit (compiled with --fmad=false, as temporal_pixel.h):
//   trustRowSums     per frame row and 8-pixel block: the float sums of the pixels with accepted
//                    history, added left to right (HistoryTrust::RowAdder)
//   trustGroup       per group of 4 x 4 blocks: each block's sums over its rows in double, the
//                    group's over its blocks, the lower trust of block and group (finish())
//   trustSoftMin     per block: 0.5 * (own + 3x3 minimum) where the minimum is below 1; counts the
//                    pixels of blocks below one half for the cut share
//   pixelTrust       per pixel: bilinear between block centres (interpolateRow())
#pragma once

#include "cuda/device_math.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace afn::cuda {

constexpr int kTrustBlockDevice = 8; ///< stages/history_trust.h kTrustBlock
constexpr int kTrustSums = 10; ///< HistoryTrust::kSums: count, sums of c, h, (c - h)^2
constexpr int kTrustCoarse = 4; ///< blocks per edge of a group (history_trust.cpp kCoarse)
/// Marks a pixel without history in TemporalBuffers::historyLength between gather and blend.
constexpr float kNoHistoryDevice = -1.0f;

/// The trust's buffers (device pointers; sizes from the frame's).
struct TrustBuffers {
    int width = 0; ///< the frame
    int height = 0;
    int blocksX = 0; ///< ceil(width / 8)
    int blocksY = 0; ///< ceil(height / 8)
    float* rowSums = nullptr; ///< height x blocksX x kTrustSums
    float* raw = nullptr; ///< blocksX x blocksY: trust before the soft minimum
    float* count = nullptr; ///< blocksX x blocksY: pixels with accepted history
    float* block = nullptr; ///< blocksX x blocksY: trust after it
    /// Pixels in blocks whose trust fell below one half (the cut share's numerator), added to
    /// with atomics; set to 0 before the frame.
    unsigned* cutPixels = nullptr;
};

AFN_HD int minIndex(int a, int b)
{
    return b < a ? b : a;
}

/// Whether the frame measures the trust (HistoryTrust::begin's `measure`).
AFN_HD bool trustMeasured(int hasHistory, float antilag)
{
    return hasHistory != 0 && antilag > 0.0f;
}

/// Row y's sums of block bx from the gathered pixels: current colour `irradiance`, reprojected
/// history `history` (3 ch), `length` kNoHistoryDevice where the pixel has none.
AFN_HD void trustRowSums(const TrustBuffers& t, const float* irradiance, const float* history,
    const float* length, int y, int bx)
{
    float s[kTrustSums] = {};
    const int x0 = bx * kTrustBlockDevice;
    const int x1 = minIndex(t.width, x0 + kTrustBlockDevice);
    for (int x = x0; x < x1; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * t.width + x;
        if (length[i] == kNoHistoryDevice)
            continue;
        s[0] += 1.0f;
        for (int k = 0; k < 3; ++k) {
            const float c = irradiance[3 * i + k], h = history[3 * i + k];
            const float d = c - h;
            s[1 + k] += c;
            s[4 + k] += h;
            s[7 + k] += d * d;
        }
    }
    float* out = t.rowSums + (static_cast<std::size_t>(y) * t.blocksX + bx) * kTrustSums;
    for (int k = 0; k < kTrustSums; ++k)
        out[k] = s[k];
}

/// Trust of a block or group from its sums (history_trust.cpp trustOf()).
AFN_HD double trustOfSums(const double* s, double antilag)
{
    if (s[0] < 16.0)
        return 1.0;
    const double n = s[0];
    double change = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double mc = s[1 + k] / n, mh = s[4 + k] / n, md = mc - mh;
        const double v = s[7 + k] / n - md * md;
        const double var = 0.0 < v ? v : 0.0;
        const double excess = fabs(md) - 3.0 * sqrt(var / n);
        double scale = mc < mh ? mh : mc; // std::max({ mc, mh, 1e-12 })
        scale = scale < 1e-12 ? 1e-12 : scale;
        const double r = excess / scale;
        change = change < r ? r : change;
    }
    const double beyond = change - 0.05;
    change = 0.0 < beyond ? beyond : 0.0;
    const double v = 1.0 - 2.0 * antilag * (1.0 < change ? 1.0 : change);
    return v < 0.0 ? 0.0 : (1.0 < v ? 1.0 : v);
}

/// The raw trust and pixel count of the blocks of group (gx, gy) (in groups of 4 x 4 blocks).
AFN_HD void trustGroup(const TrustBuffers& t, float antilag, int gx, int gy)
{
    const int bx0 = gx * kTrustCoarse, by0 = gy * kTrustCoarse;
    const int cols = minIndex(kTrustCoarse, t.blocksX - bx0);
    const int rows = minIndex(kTrustCoarse, t.blocksY - by0);
    double sums[kTrustCoarse][kTrustCoarse][kTrustSums];
    double g[kTrustSums] = {};
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            double* s = sums[r][c];
            for (int k = 0; k < kTrustSums; ++k)
                s[k] = 0.0;
            const int by = by0 + r;
            const int y1 = minIndex(t.height, (by + 1) * kTrustBlockDevice);
            for (int y = by * kTrustBlockDevice; y < y1; ++y) {
                const float* v
                    = t.rowSums + (static_cast<std::size_t>(y) * t.blocksX + bx0 + c) * kTrustSums;
                for (int k = 0; k < kTrustSums; ++k)
                    s[k] += v[k];
            }
            t.count[static_cast<std::size_t>(by) * t.blocksX + bx0 + c] = static_cast<float>(s[0]);
        }
    for (int r = 0; r < rows; ++r) // the CPU's order: rows, then the blocks of each row
        for (int c = 0; c < cols; ++c)
            for (int k = 0; k < kTrustSums; ++k)
                g[k] += sums[r][c][k];
    const double coarse = trustOfSums(g, antilag);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double fine = trustOfSums(sums[r][c], antilag);
            t.raw[static_cast<std::size_t>(by0 + r) * t.blocksX + bx0 + c]
                = static_cast<float>(fine < coarse ? fine : coarse);
        }
}

/// The softened trust of block (bx, by); returns the pixels it adds to the cut share.
AFN_HD unsigned trustSoftMin(const TrustBuffers& t, int bx, int by)
{
    float lo = 1.0f;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = bx + dx, qy = by + dy;
            if (qx >= 0 && qy >= 0 && qx < t.blocksX && qy < t.blocksY)
                lo = minOf(lo, t.raw[static_cast<std::size_t>(qy) * t.blocksX + qx]);
        }
    const std::size_t i = static_cast<std::size_t>(by) * t.blocksX + bx;
    const float v = lo == 1.0f ? 1.0f : 0.5f * (t.raw[i] + lo);
    t.block[i] = v;
    return v < 0.5f ? static_cast<unsigned>(t.count[i]) : 0u;
}

/// Bilinear position of pixel coordinate p between block centres (history_trust.cpp
/// blockCoordinate()).
AFN_HD void trustCoordinate(int p, int count, int& b0, int& b1, float& w)
{
    const float f = (static_cast<float>(p) - 0.5f * (kTrustBlockDevice - 1))
        / static_cast<float>(kTrustBlockDevice);
    if (f <= 0.0f) {
        b0 = b1 = 0;
        w = 0.0f;
        return;
    }
    b0 = minIndex(static_cast<int>(f), count - 1);
    b1 = minIndex(b0 + 1, count - 1);
    w = b1 == b0 ? 0.0f : f - static_cast<float>(b0);
}

/// The trust of pixel (x, y).
AFN_HD float pixelTrust(const TrustBuffers& t, int x, int y)
{
    int bx0, bx1, by0, by1;
    float wx, wy;
    trustCoordinate(x, t.blocksX, bx0, bx1, wx);
    trustCoordinate(y, t.blocksY, by0, by1, wy);
    auto at
        = [&](int bx, int by) { return t.block[static_cast<std::size_t>(by) * t.blocksX + bx]; };
    const float t0 = at(bx0, by0), t1 = at(bx1, by0), b0 = at(bx0, by1), b1 = at(bx1, by1);
    const float top = t0 + wx * (t1 - t0);
    const float bottom = b0 + wx * (b1 - b0);
    return minOf(maxOf(top + wy * (bottom - top), 0.0f), 1.0f);
}

} // namespace afn::cuda
