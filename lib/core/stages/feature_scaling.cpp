// SPDX-License-Identifier: Apache-2.0
// Auxiliary-feature scaling of the learned methods' inputs (see stages/feature_scaling.h), in
// parallel over blocks of rows (each value depends on its own pixel and, for depth, on the
// frame's range: the same results for any split).
#include "stages/feature_scaling.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>
#include <mutex>

namespace afn {

void normalToUnitRange(const Image& normal, int w, int h, Image& out)
{
    out.resize(w, h, 3);
    if (normal.empty()) {
        out.fill(0.5f);
        return;
    }
    parallelRows(h, [&](int y0, int y1) {
        const float* in = normal.at(0, y0);
        float* o = out.at(0, y0);
        for (std::size_t k = 0, n = static_cast<std::size_t>(y1 - y0) * w * 3; k < n; ++k)
            o[k]
                = std::isfinite(in[k]) ? std::min(std::max(in[k] * 0.5f + 0.5f, 0.0f), 1.0f) : 0.5f;
    });
}

void depthToUnitRange(const Image& depth, int w, int h, Image& out)
{
    out.resize(w, h, 1);
    if (depth.empty()) {
        out.fill(0.0f);
        return;
    }
    auto valid = [](float z) { return std::isfinite(z) && std::fabs(z) < kDepthSky; };
    // The valid depths' minimum and maximum, per block of rows, then over the blocks (the same
    // values in any order).
    float lo = 0.0f, hi = 0.0f;
    bool any = false;
    std::mutex merge;
    parallelRows(h, [&](int y0, int y1) {
        const float* d = depth.at(0, y0);
        float blo = 0.0f, bhi = 0.0f;
        bool bany = false;
        for (std::size_t k = 0, n = static_cast<std::size_t>(y1 - y0) * w; k < n; ++k) {
            const float z = d[k];
            if (!valid(z))
                continue;
            blo = bany ? std::min(blo, z) : z;
            bhi = bany ? std::max(bhi, z) : z;
            bany = true;
        }
        if (!bany)
            return;
        const std::lock_guard<std::mutex> lock(merge);
        lo = any ? std::min(lo, blo) : blo;
        hi = any ? std::max(hi, bhi) : bhi;
        any = true;
    });
    // Same arithmetic as numpy in color.py: float32 (z - lo) times the float32-rounded 1/(hi - lo).
    const float scale = hi > lo ? static_cast<float>(1.0 / (static_cast<double>(hi) - lo)) : 0.0f;
    parallelRows(h, [&](int y0, int y1) {
        const float* d = depth.at(0, y0);
        float* o = out.at(0, y0);
        for (std::size_t k = 0, n = static_cast<std::size_t>(y1 - y0) * w; k < n; ++k) {
            const float v = valid(d[k]) ? (d[k] - lo) * scale : 1.0f;
            o[k] = std::min(std::max(v, 0.0f), 1.0f);
        }
    });
}

} // namespace afn
