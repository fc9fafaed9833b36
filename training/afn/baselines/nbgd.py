# SPDX-License-Identifier: Apache-2.0
"""NBGD: neural bilateral grid denoiser (Meng, Zheng, Lv, Bao, Wang, Huo, Wang, Chen; EGSR 2020),
as implemented by afn. C++ inference: lib/core/methods/nbgd/ (grid conventions in
lib/core/methods/nbgd/bilateral_grid.h, the same as here).

From the paper and its public code: a guide network of two 5x5 convs (-> 20, leaky ReLU -> 5,
sigmoid): three guides (x 255) and two blend weights; three bilateral grids with (spatial, range)
steps (4, 4), (8, 8), (16, 16); tent splat normalised per cell; trilinear slice skipping empty
cells; output ``w1 g1 + w2 g2 + (1 - w1 - w2) g3``, remodulated by albedo; L1 on the tone-mapped
output.

Chosen here (the paper leaves it open):

* Input: :mod:`afn.baselines.inputs` (T(cta), albedo, normal01, depth01); the grids splat the
  linear HDR TA-1spp colour cta; grid k is splatted and sliced with guide k.
* Grid coordinates of pixel (x, y) with guide g in [0, 255]: (x / ss, y / ss, g / sr) in cell
  units; the grid has floor((W-1)/ss) + 2 x floor((H-1)/ss) + 2 x floor(255/sr) + 2 cells, so the
  upper trilinear neighbour of every pixel exists. Splat: each pixel adds (c, 1) x the trilinear
  (tent, support 2 cells = 2 ss pixels) weight to its 8 neighbouring cells; a cell's value is its
  colour sum / its weight sum when the weight sum is > 0 (else the cell is empty). Slice: trilinear
  interpolation at the same coordinates over the non-empty neighbours only, renormalised by their
  interpolation weights (a pixel's own cells are never all empty, so the sum is > 0).
* Leaky ReLU slope 0.2 (the official TensorFlow code's tf.nn.leaky_relu default).
* Blend weights are two independent sigmoids (as in the paper); 1 - w1 - w2 may be negative.

Cost (from :func:`cost_per_pixel`, FLOP = 2 per multiply-add): guide network 15,000 FLOP; splat
and slice 3 grids x 8 cells x (4 + 4) ~ 200 FLOP per pixel (memory-bound scatter/gather);
7,525 parameters.
"""

import torch
import torch.nn.functional as F
from torch import nn

from .inputs import INPUT_CHANNELS, network_input

HIDDEN = 20
GUIDE_OUT = 5
GRIDS = ((4, 4), (8, 8), (16, 16))   # (spatial step in pixels, range step in guide units)
GUIDE_SCALE = 255.0
LEAKY_SLOPE = 0.2


def grid_shape(h, w, ss, sr):
    """(grid height, grid width, range cells) for an h x w image."""
    return (h - 1) // ss + 2, (w - 1) // ss + 2, int(GUIDE_SCALE // sr) + 2


def _corners(h, w, guide, ss, sr):
    """Yields (flat cell index (B, H*W) long, trilinear weight (B, H*W)) for the 8 neighbours."""
    gh, gw, gr = grid_shape(h, w, ss, sr)
    dev = guide.device
    y = torch.arange(h, device=dev, dtype=torch.float32) / ss
    x = torch.arange(w, device=dev, dtype=torch.float32) / ss
    y0, x0 = torch.floor(y), torch.floor(x)
    fy, fx = (y - y0)[:, None], (x - x0)[None, :]
    y0, x0 = y0.long()[:, None], x0.long()[None, :]
    r = torch.clamp(guide[:, 0], 0.0, GUIDE_SCALE) / sr          # (B, H, W)
    r0 = torch.floor(r).detach()
    fr = r - r0
    r0 = r0.long()
    b = guide.shape[0]
    for dy in (0, 1):
        wy = fy if dy else 1.0 - fy
        for dx in (0, 1):
            wx = fx if dx else 1.0 - fx
            for dr in (0, 1):
                wr = fr if dr else 1.0 - fr
                idx = ((y0 + dy) * gw + (x0 + dx)) * gr + (r0 + dr)
                yield idx.reshape(b, -1), (wy * wx * wr).reshape(b, -1)


def bilateral_filter(color, guide, ss, sr):
    """Splat ``color`` into a bilateral grid by ``guide`` and slice it back.

    Args:
        color: (B, C, H, W) linear HDR.
        guide: (B, 1, H, W) in [0, 255].
        ss, sr: spatial step (pixels) and range step (guide units).

    Returns:
        (B, C, H, W) sliced colour (module docstring: conventions).
    """
    b, c, h, w = color.shape
    gh, gw, gr = grid_shape(h, w, ss, sr)
    vals = torch.cat([color, torch.ones_like(color[:, :1])], 1).reshape(b, c + 1, -1)
    grid = color.new_zeros(b, c + 1, gh * gw * gr)
    corners = list(_corners(h, w, guide, ss, sr))
    for idx, wt in corners:
        grid = grid.scatter_add(2, idx[:, None].expand(-1, c + 1, -1), vals * wt[:, None])
    wsum = grid[:, c:]
    occupied = (wsum > 0).to(color.dtype)
    cells = grid[:, :c] / torch.where(wsum > 0, wsum, torch.ones_like(wsum))
    num = color.new_zeros(b, c, h * w)
    den = color.new_zeros(b, 1, h * w)
    for idx, wt in corners:
        g = cells.gather(2, idx[:, None].expand(-1, c, -1))
        o = occupied.gather(2, idx[:, None])
        num = num + (wt[:, None] * o) * g
        den = den + wt[:, None] * o
    return (num / den.clamp_min(1e-12)).reshape(b, c, h, w)


class NBGD(nn.Module):
    """Guide network + three bilateral grids (module docstring).

    Example:
        >>> net = NBGD()
        >>> o = net(cta, albedo, normal01, depth01)["o"]  # demodulated; color.remodulate after
    """

    def __init__(self):
        super().__init__()
        self.guide1 = nn.Conv2d(INPUT_CHANNELS, HIDDEN, 5, padding=2)
        self.guide2 = nn.Conv2d(HIDDEN, GUIDE_OUT, 5, padding=2)

    def guides(self, cta, albedo, normal01, depth01):
        """(B, 5, H, W): sigmoid outputs; channels 0-2 x 255 are the guides, 3-4 the weights."""
        x = network_input(cta, albedo, normal01, depth01)
        x = F.leaky_relu(self.guide1(x), LEAKY_SLOPE)
        return torch.sigmoid(self.guide2(x))

    def forward(self, cta, albedo, normal01, depth01):
        """Inputs (B, C, H, W) as afn's; returns {"o", "guides", "g1", "g2", "g3"}."""
        s = self.guides(cta, albedo, normal01, depth01)
        sliced = [bilateral_filter(cta, s[:, k:k + 1] * GUIDE_SCALE, ss, sr)
                  for k, (ss, sr) in enumerate(GRIDS)]
        w1, w2 = s[:, 3:4], s[:, 4:5]
        o = w1 * sliced[0] + w2 * sliced[1] + (1.0 - w1 - w2) * sliced[2]
        return {"o": o, "guides": s, "g1": sliced[0], "g2": sliced[1], "g3": sliced[2]}


def loss(output, target):
    """L1 on the tone-mapped remodulated output (T = clip(max(x, 0)^(1/2.2), 0, 1))."""
    from ..color import tonemap
    return torch.mean(torch.abs(tonemap(output) - tonemap(target)))


def cost_per_pixel():
    """FLOP per pixel (2 per multiply-add) and parameters."""
    net = 2 * 25 * (INPUT_CHANNELS * HIDDEN + HIDDEN * GUIDE_OUT)
    grids = len(GRIDS) * 8 * (4 + 4) + 3 * 3   # splat + slice per corner, blend
    params = sum(p.numel() for p in NBGD().parameters())
    return {"network": net, "grids": grids, "total": net + grids, "parameters": params}
