// SPDX-License-Identifier: Apache-2.0
// MR-KP's filtering and level blending (see methods/mrkp/kernels.h).
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

void blendLevels(Image& fine, const Image& coarse, const Image& head)
{
    const int w = fine.width(), h = fine.height();
    if (coarse.width() * 2 != w || coarse.height() * 2 != h || head.width() != w
        || head.height() != h)
        throwInvalidArgument("MR-KP: level sizes differ");
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
                    const float a = 1.0f / (1.0f + std::exp(-head.at(x, y)[kTaps]));
                    float* o = fine.at(x, y);
                    for (int c = 0; c < 3; ++c)
                        o[c] = o[c] - a * mean[c] + a * lo[c];
                }
            }
    });
}

} // namespace afn::mrkp
