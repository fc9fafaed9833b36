// SPDX-License-Identifier: Apache-2.0
#include "methods/wskpn/weight_sharing_filter.h"

#include "base/parallel.h"
#include "methods/wskpn/network.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace afn::wskpn {

namespace {

constexpr float kLogitClamp = 20.0f;
constexpr float kSumEps = 1e-30f;
constexpr int kSums = 4 * kWindows; // per window: w*r, w*g, w*b, w

int radius(int index)
{
    return index + 1; // windows 3, 5, ..., 13: radius 1 ... 6
}

} // namespace

void weightSharingFilter(
    const Image& color, const Image& head, Image& products, Image& scratch, Image& out)
{
    const int w = color.width(), h = color.height();
    // 1. Products per pixel: (w_i c, w_i) for every window i.
    products.resize(w, h, kSums);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* lg = head.at(x, y);
                const float* c = color.at(x, y);
                float* p = products.at(x, y);
                for (int i = 0; i < kWindows; ++i) {
                    const float wi = std::exp(std::min(std::max(lg[i], -kLogitClamp), kLogitClamp));
                    p[4 * i + 0] = wi * c[0];
                    p[4 * i + 1] = wi * c[1];
                    p[4 * i + 2] = wi * c[2];
                    p[4 * i + 3] = wi;
                }
            }
    });
    // 2. Horizontal box sums into scratch.
    scratch.resize(w, h, kSums);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float* s = scratch.at(x, y);
                for (int i = 0; i < kWindows; ++i) {
                    const int r = radius(i);
                    float acc[4] = { 0, 0, 0, 0 };
                    for (int xx = std::max(x - r, 0); xx <= std::min(x + r, w - 1); ++xx) {
                        const float* p = products.at(xx, y) + 4 * i;
                        for (int k = 0; k < 4; ++k)
                            acc[k] += p[k];
                    }
                    std::copy_n(acc, 4, s + 4 * i);
                }
            }
    });
    // 3. Vertical box sums, ratios, softmax fusion.
    out.resize(w, h, 3);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* lg = head.at(x, y) + kWindows;
                float mx = lg[0];
                for (int i = 1; i < kWindows; ++i)
                    mx = std::max(mx, lg[i]);
                float f[kWindows], fsum = 0.0f;
                for (int i = 0; i < kWindows; ++i)
                    fsum += f[i] = std::exp(lg[i] - mx);
                float o[3] = { 0, 0, 0 };
                for (int i = 0; i < kWindows; ++i) {
                    const int r = radius(i);
                    float acc[4] = { 0, 0, 0, 0 };
                    for (int yy = std::max(y - r, 0); yy <= std::min(y + r, h - 1); ++yy) {
                        const float* s = scratch.at(x, yy) + 4 * i;
                        for (int k = 0; k < 4; ++k)
                            acc[k] += s[k];
                    }
                    if (!(acc[3] > kSumEps))
                        continue;
                    const float g = f[i] / fsum;
                    for (int k = 0; k < 3; ++k)
                        o[k] += g * (acc[k] / acc[3]);
                }
                std::copy_n(o, 3, out.at(x, y));
            }
    });
}

} // namespace afn::wskpn
