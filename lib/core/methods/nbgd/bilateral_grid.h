// SPDX-License-Identifier: Apache-2.0
// The bilateral grid of NBGD (Meng et al. 2020), with the conventions of
// training/afn/baselines/nbgd.py (the reference for the parity test):
//
// - Coordinates. Pixel (x, y) with guide g (clamped to [0, 255]) sits at grid position
//   (u, v, r) = (x / ss, y / ss, g / sr) in cell units (float32 divisions), ss = spatial step in
//   pixels, sr = range step in guide units. Cell (i, j, l) is the grid point at integer (i, j, l):
//   pixel 0 lies exactly on cell 0.
// - Size. floor((W-1)/ss) + 2 cells across, floor((H-1)/ss) + 2 down, floor(255/sr) + 2 range
//   cells, so the upper trilinear neighbour of every pixel exists. Layout [v][u][r][channel + 1].
// - Splat. Each pixel adds (c, 1) times its trilinear (tent) weight
//   (1 - |u - i|)(1 - |v - j|)(1 - |r - l|) to its 8 neighbouring cells: a tent of 2 cells = 2 ss
//   pixels spatially and 2 sr guide units in range. A cell's value is its colour sum divided by its
//   weight sum when that is > 0; a cell with weight sum 0 is empty.
// - Slice. Trilinear interpolation at the pixel's own position over its non-empty neighbours,
//   divided by the sum of their interpolation weights (> 0: the pixel's own splat reached them;
//   guarded by 1e-12).
// The splat runs serially per grid (each call is one grid; callers run grids in parallel); the
// slice is parallel over rows.
#pragma once

#include "base/image.h"

#include <vector>

namespace afn::nbgd {

/// The guide's full range (the network's sigmoid x 255).
constexpr float kGuideScale = 255.0f;

class BilateralGrid {
public:
    /// out (w x h x c) = slice(splat(color, guide)) for a colour of 1 to 4 channels; `guide`
    /// (same size) holds g in channel `gc`.
    void filter(const Image& color, const Image& guide, int gc, int ss, int sr, Image& out);

private:
    std::vector<float> m_cells; ///< [v][u][r][c + 1]
};

} // namespace afn::nbgd
