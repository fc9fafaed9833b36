// SPDX-License-Identifier: Apache-2.0
// Auxiliary-feature scaling of the learned methods' inputs (see stages/feature_scaling.h).
#include "stages/feature_scaling.h"

#include <algorithm>
#include <cmath>

namespace afn {

void normalToUnitRange(const Image& normal, int w, int h, Image& out)
{
    out.resize(w, h, 3);
    if (normal.empty()) {
        out.fill(0.5f);
        return;
    }
    for (std::size_t k = 0; k < out.size(); ++k) {
        const float n = normal.data()[k];
        out.data()[k] = std::isfinite(n) ? std::min(std::max(n * 0.5f + 0.5f, 0.0f), 1.0f) : 0.5f;
    }
}

void depthToUnitRange(const Image& depth, int w, int h, Image& out)
{
    out.resize(w, h, 1);
    if (depth.empty()) {
        out.fill(0.0f);
        return;
    }
    auto valid = [](float z) { return std::isfinite(z) && std::fabs(z) < kDepthSky; };
    float lo = 0.0f, hi = 0.0f;
    bool any = false;
    for (std::size_t k = 0; k < out.size(); ++k) {
        const float z = depth.data()[k];
        if (!valid(z))
            continue;
        lo = any ? std::min(lo, z) : z;
        hi = any ? std::max(hi, z) : z;
        any = true;
    }
    // Same arithmetic as numpy in color.py: float32 (z - lo) times the float32-rounded 1/(hi - lo).
    const float scale = hi > lo ? static_cast<float>(1.0 / (static_cast<double>(hi) - lo)) : 0.0f;
    for (std::size_t k = 0; k < out.size(); ++k) {
        const float z = depth.data()[k];
        const float v = valid(z) ? (z - lo) * scale : 1.0f;
        out.data()[k] = std::min(std::max(v, 0.0f), 1.0f);
    }
}

} // namespace afn
