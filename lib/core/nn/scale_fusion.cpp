// SPDX-License-Identifier: Apache-2.0
// Fusion of two scales (see nn/scale_fusion.h).
#include "nn/scale_fusion.h"

#include "base/exception.h"
#include "base/parallel.h"

#include <cmath>

namespace afn::nn {

void fuseScales(Image& fine, const Image& coarse, const Image& logits, int channel)
{
    const int w = fine.width(), h = fine.height();
    if (fine.channels() != 3 || coarse.channels() != 3 || coarse.width() * 2 != w
        || coarse.height() * 2 != h || logits.width() != w || logits.height() != h || channel < 0
        || channel >= logits.channels())
        throwInvalidArgument("scale fusion: level sizes differ");
    parallelRows(h / 2, [&](int y0, int y1) {
        for (int cy = y0; cy < y1; ++cy)
            for (int cx = 0; cx < w / 2; ++cx) {
                float mean[3];
                const float* p00 = fine.at(2 * cx, 2 * cy);
                const float* p10 = fine.at(2 * cx + 1, 2 * cy);
                const float* p01 = fine.at(2 * cx, 2 * cy + 1);
                const float* p11 = fine.at(2 * cx + 1, 2 * cy + 1);
                for (int c = 0; c < 3; ++c) // PyTorch avg_pool2d: row-order sum, then / 4
                    mean[c] = (p00[c] + p10[c] + p01[c] + p11[c]) / 4.0f;
                const float* lo = coarse.at(cx, cy);
                for (int t = 0; t < 4; ++t) {
                    const int x = 2 * cx + (t & 1), y = 2 * cy + (t >> 1);
                    const float a = 1.0f / (1.0f + std::exp(-logits.at(x, y)[channel]));
                    float* o = fine.at(x, y);
                    for (int c = 0; c < 3; ++c)
                        o[c] = o[c] - a * mean[c] + a * lo[c];
                }
            }
    });
}

} // namespace afn::nn
