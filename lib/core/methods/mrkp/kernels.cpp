// SPDX-License-Identifier: Apache-2.0
// MR-KP's filtering (see methods/mrkp/kernels.h).
#include "methods/mrkp/kernels.h"

#include "base/exception.h"
#include "base/parallel.h"

#include <algorithm>
#include <cmath>

namespace afn::mrkp {

namespace {

constexpr float kKernelEps = 1e-8f;

} // namespace

void applyKernels(const Image& color, const Image& head, Image& filtered)
{
    const int w = color.width(), h = color.height();
    if (head.width() != w || head.height() != h || head.channels() != kHeadChannels)
        throwInvalidArgument("MR-KP: kernel head and image sizes differ");
    filtered.resize(w, h, 3);
    constexpr int r = kKernelSize / 2;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* k = head.at(x, y);
                float acc[3] = { 0.0f, 0.0f, 0.0f };
                float sum = 0.0f;
                for (int j = 0; j < kTaps; ++j) {
                    const float wj = std::max(k[j], 0.0f);
                    const int sy = std::min(std::max(y + j / kKernelSize - r, 0), h - 1);
                    const int sx = std::min(std::max(x + j % kKernelSize - r, 0), w - 1);
                    const float* c = color.at(sx, sy);
                    acc[0] += wj * c[0];
                    acc[1] += wj * c[1];
                    acc[2] += wj * c[2];
                    sum += wj;
                }
                float* o = filtered.at(x, y);
                const float inv = 1.0f / (sum + kKernelEps);
                for (int c = 0; c < 3; ++c)
                    o[c] = acc[c] * inv;
            }
    });
}

} // namespace afn::mrkp
