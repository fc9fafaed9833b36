// SPDX-License-Identifier: Apache-2.0
// ONND's local-contrast gate (see methods/onnd/contrast_gate.h).
#include "methods/onnd/contrast_gate.h"

#include "base/parallel.h"

#include <algorithm>

namespace afn::onnd {

void contrastGate(const Image& c, Image& gate)
{
    const int w = c.width(), h = c.height();
    gate.resize(w, h, 1);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float contrast = 0.0f;
                for (int k = 0; k < 3; ++k) {
                    float hi = 0.0f, lo = 0.0f;
                    bool first = true;
                    for (int dy = -kGateRadius; dy <= kGateRadius; ++dy)
                        for (int dx = -kGateRadius; dx <= kGateRadius; ++dx) {
                            const int sx = std::clamp(x + dx, 0, w - 1);
                            const int sy = std::clamp(y + dy, 0, h - 1);
                            const float v = std::max(c(sx, sy, k), 0.0f);
                            hi = first ? v : std::max(hi, v);
                            lo = first ? v : std::min(lo, v);
                            first = false;
                        }
                    contrast = std::max(contrast, (hi - lo) / (hi + lo + kGateEps));
                }
                gate(x, y, 0) = std::min(kGateGain * contrast, 1.0f);
            }
    });
}

} // namespace afn::onnd
