// SPDX-License-Identifier: Apache-2.0
// afn's learned albedo trust (see methods/afn/albedo_trust.h).
#include "methods/afn/albedo_trust.h"

#include "stages/demodulate.h"

#include <algorithm>
#include <cmath>

namespace afn::afnet {

namespace {

/// s = max(a, eps) / max(a + (1 - a) t, eps), as training/afn/model.py albedo_trust_scale.
inline float trustScale(float a, float t)
{
    const float blended = a + (1.0f - a) * t;
    return std::max(a, kAlbedoEpsilon) / std::max(blended, kAlbedoEpsilon);
}

} // namespace

void albedoTrustRows(const nn::Conv& headG, const Image& e1, int y0, int y1, Image& t)
{
    if (y1 <= y0)
        return;
    headG.runRows(nullptr, e1, y0, y1, t.at(0, y0), t.width(), 1, false);
    float* v = t.at(0, y0);
    const std::size_t n = static_cast<std::size_t>(y1 - y0) * t.width();
    for (std::size_t i = 0; i < n; ++i)
        v[i] = 1.0f / (1.0f + std::exp(-v[i]));
}

void applyAlbedoTrustRows(const Image& x, const Image& t, int y0, int y1, Image& color)
{
    const int w = color.width();
    for (int y = y0; y < y1; ++y) {
        const float* tr = t.at(0, y / 2);
        for (int xx = 0; xx < w; ++xx) {
            const float* a = x.at(xx, y) + 6;
            float* c = color.at(xx, y);
            const float tv = tr[xx / 2];
            for (int k = 0; k < 3; ++k)
                c[k] *= trustScale(a[k], tv);
        }
    }
}

void undoAlbedoTrustRows(
    const Image& x, const Image& t, int y0, int y1, int width, float* dst, long dstRow)
{
    const int w = std::min(width, x.width());
    for (int y = y0; y < y1; ++y) {
        const float* tr = t.at(0, y / 2);
        float* o = dst + (y - y0) * dstRow;
        for (int xx = 0; xx < w; ++xx) {
            const float* a = x.at(xx, y) + 6;
            const float tv = tr[xx / 2];
            for (int k = 0; k < 3; ++k)
                o[3 * xx + k] /= trustScale(a[k], tv);
        }
    }
}

} // namespace afn::afnet
