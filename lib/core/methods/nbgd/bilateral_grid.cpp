// SPDX-License-Identifier: Apache-2.0
#include "methods/nbgd/bilateral_grid.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>

namespace afn::nbgd {

namespace {

/// The 8 neighbouring cells of a pixel: base index and fractional parts.
struct Corners {
    long base; ///< cell (i0, j0, l0) as a cell index
    float fx, fy, fr;
};

Corners corners(int x, int y, float g, int ss, int sr, int gw, int gr)
{
    const float u = static_cast<float>(x) / static_cast<float>(ss);
    const float v = static_cast<float>(y) / static_cast<float>(ss);
    // clamp(g, 0, 255); NaN (never produced from sanitised inputs) goes to 0, never out of the grid
    const float r = (g >= 0.0f ? std::min(g, kGuideScale) : 0.0f) / static_cast<float>(sr);
    const float u0 = std::floor(u), v0 = std::floor(v), r0 = std::floor(r);
    const long base
        = (static_cast<long>(v0) * gw + static_cast<long>(u0)) * gr + static_cast<long>(r0);
    return { base, u - u0, v - v0, r - r0 };
}

} // namespace

void BilateralGrid::filter(
    const Image& color, const Image& guide, int gc, int ss, int sr, Image& out)
{
    const int w = color.width(), h = color.height(), c = color.channels(), cs = c + 1;
    const int gw = (w - 1) / ss + 2, gh = (h - 1) / ss + 2;
    const int gr = static_cast<int>(kGuideScale / static_cast<float>(sr)) + 2;
    const long dU = gr, dV = static_cast<long>(gw) * gr; // cell index steps
    m_cells.assign(static_cast<std::size_t>(gh) * gw * gr * cs, 0.0f);
    float* cells = m_cells.data();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Corners k = corners(x, y, guide(x, y, gc), ss, sr, gw, gr);
            const float* px = color.at(x, y);
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    for (int dr = 0; dr < 2; ++dr) {
                        const float wt = (dy ? k.fy : 1.0f - k.fy) * (dx ? k.fx : 1.0f - k.fx)
                            * (dr ? k.fr : 1.0f - k.fr);
                        float* cell = cells + (k.base + dy * dV + dx * dU + dr) * cs;
                        for (int ch = 0; ch < c; ++ch)
                            cell[ch] += px[ch] * wt;
                        cell[c] += wt;
                    }
        }
    const std::size_t n = static_cast<std::size_t>(gh) * gw * gr;
    for (std::size_t i = 0; i < n; ++i) {
        float* cell = cells + i * cs;
        if (cell[c] > 0.0f)
            for (int ch = 0; ch < c; ++ch)
                cell[ch] /= cell[c];
    }
    out.resize(w, h, c);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const Corners k = corners(x, y, guide(x, y, gc), ss, sr, gw, gr);
                float num[4] = { 0, 0, 0, 0 }, den = 0.0f;
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx)
                        for (int dr = 0; dr < 2; ++dr) {
                            const float* cell = cells + (k.base + dy * dV + dx * dU + dr) * cs;
                            if (!(cell[c] > 0.0f))
                                continue;
                            const float wt = (dy ? k.fy : 1.0f - k.fy) * (dx ? k.fx : 1.0f - k.fx)
                                * (dr ? k.fr : 1.0f - k.fr);
                            for (int ch = 0; ch < c && ch < 4; ++ch)
                                num[ch] += wt * cell[ch];
                            den += wt;
                        }
                float* o = out.at(x, y);
                for (int ch = 0; ch < c && ch < 4; ++ch)
                    o[ch] = num[ch] / std::max(den, 1e-12f);
            }
    });
}

} // namespace afn::nbgd
