# SPDX-License-Identifier: Apache-2.0
"""BMFR temporal accumulation in numpy, the same algorithm as the C++ core's "ta"
(lib/core/reproject.{h,cpp}, lib/core/temporal_accumulation.{h,cpp}); it makes the TA-1spp input
of the training data. Only the motion-vector path is implemented (the rendered data has motion):

* previous position of pixel (x, y): (x + mx, y + my), motion in pixels, y down (row order),
  pointing to where the surface was in the previous frame;
* four bilinear taps around it, each accepted when inside the image and
  - position (when given): |p_prev(tap) - p|^2 == 0 or < (position_limit * footprint(p))^2, the
    footprint being max over the two axes of the smaller distance to the left/right (top/bottom)
    neighbour's position; else depth (when given): |z_prev - z| == 0 or < depth_limit * |z|;
  - normal (when given): neither normal zero and |n_prev - n|^2 < normal_limit_sq;
* history = sum(w * prev) / sum(w) over accepted taps (weights > 0, in tap order TL, TR, BL, BR);
* if sum(w) > 0: alpha = max(1 / (spp + 1), alpha_min), acc = prev + alpha * (c - prev),
  spp = min(spp + 1, 255) (1 if alpha == 1); else acc = c, spp = 1.

All arithmetic is float32 in the C++ order, so results are meant to agree with the core bit for bit
on the same inputs (an exact cross-test belongs to the temporal-accumulation issue).
"""

import numpy as np

MAX_HISTORY = 255.0


class TemporalAccumulator:
    """Stateful TA over a sequence; call :meth:`accumulate` once per frame in order.

    Args:
        alpha_min: minimum blend factor (BMFR: 0.2).
        position_limit: in pixel footprints (C++ ReprojectSettings.positionLimit, default 4).
        normal_limit_sq: squared unit-normal distance (default 0.25).
        depth_limit: relative depth limit, only without positions (default 0.1).
    """

    def __init__(self, alpha_min=0.2, position_limit=4.0, normal_limit_sq=0.25, depth_limit=0.1):
        self.alpha_min = np.float32(alpha_min)
        self.position_limit = np.float32(position_limit)
        self.normal_limit_sq = np.float32(normal_limit_sq)
        self.depth_limit = np.float32(depth_limit)
        self.reset()

    def reset(self):
        self.prev = None   # dict: color, spp, position, normal, depth

    def accumulate(self, irradiance, motion=None, position=None, normal=None, depth=None):
        """Blend one frame into the history.

        Args:
            irradiance: (H, W, 3) float32 demodulated colour, finite, >= 0.
            motion: (H, W, 2) pixels, y down, to the previous frame (None: static camera).
            position: (H, W, 3) world position or None.
            normal: (H, W, 3) unit shading normal or None.
            depth: (H, W) or (H, W, 1) linear depth or None (used only without position).

        Returns:
            (acc (H, W, 3) float32, spp (H, W) float32 history length).
        """
        c = np.asarray(irradiance, np.float32)
        h, w = c.shape[:2]
        if depth is not None:
            depth = np.asarray(depth, np.float32).reshape(h, w)
        acc, spp = c.copy(), np.ones((h, w), np.float32)
        p = self.prev
        if p is not None and p["color"].shape == c.shape:
            prev_c, ws, prev_s = self._history(c, motion, position, normal, depth)
            has = ws > 0
            alpha = np.maximum(np.float32(1) / (prev_s + np.float32(1)), self.alpha_min)
            blended = prev_c + alpha[..., None] * (c - prev_c)
            acc = np.where(has[..., None], blended, c).astype(np.float32)
            grown = np.where(alpha < 1, np.minimum(prev_s + np.float32(1), np.float32(MAX_HISTORY)),
                             np.float32(1))
            spp = np.where(has, grown, np.float32(1)).astype(np.float32)
        self.prev = {"color": acc, "spp": spp, "position": position, "normal": normal,
                     "depth": depth}
        return acc, spp

    def _history(self, c, motion, position, normal, depth):
        h, w = c.shape[:2]
        p = self.prev
        ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
        if motion is not None:
            px = xs + motion[..., 0].astype(np.float32)
            py = ys + motion[..., 1].astype(np.float32)
        else:
            px, py = xs.copy(), ys.copy()
        ok = (np.abs(px) < 1e7) & (np.abs(py) < 1e7)
        px, py = np.where(ok, px, 0).astype(np.float32), np.where(ok, py, 0).astype(np.float32)
        fx0, fy0 = np.floor(px), np.floor(py)
        fx, fy = (px - fx0).astype(np.float32), (py - fy0).astype(np.float32)
        x0, y0 = fx0.astype(np.int64), fy0.astype(np.int64)
        one = np.float32(1)
        bw = [(one - fx) * (one - fy), fx * (one - fy), (one - fx) * fy, fx * fy]
        use_pos = position is not None and p["position"] is not None
        lim = self.position_limit * _footprint(position) if use_pos else None
        out_c = np.zeros_like(c)
        out_s = np.zeros((h, w), np.float32)
        ws = np.zeros((h, w), np.float32)
        for k in range(4):
            tx, ty = x0 + (k & 1), y0 + (k >> 1)
            inside = ok & (tx >= 0) & (ty >= 0) & (tx < w) & (ty < h)
            cx, cy = np.clip(tx, 0, w - 1), np.clip(ty, 0, h - 1)
            acc = inside.copy()
            if use_pos:
                d2 = _dist2(p["position"][cy, cx], position)
                acc &= (d2 == 0) | (d2 < lim * lim)
            elif depth is not None and p["depth"] is not None:
                dz = np.abs(p["depth"][cy, cx] - depth)
                acc &= (dz == 0) | (dz < self.depth_limit * np.abs(depth))
            if normal is not None and p["normal"] is not None:
                n_prev = p["normal"][cy, cx]
                zero = ~normal.any(-1) | ~n_prev.any(-1)
                acc &= ~zero & (_dist2(n_prev, normal) < self.normal_limit_sq)
            wk = np.where(acc & (bw[k] > 0), bw[k], np.float32(0)).astype(np.float32)
            out_c += wk[..., None] * p["color"][cy, cx]
            out_s += wk * p["spp"][cy, cx]
            ws += wk
        safe = np.where(ws > 0, ws, one)
        return out_c / safe[..., None], ws, out_s / safe


def _dist2(a, b):
    d = (a - b).astype(np.float32)
    return d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1] + d[..., 2] * d[..., 2]


def _footprint(pos):
    """World size of each pixel: max over axes of the smaller neighbour distance (C++ footprint)."""
    h, w = pos.shape[:2]
    big = np.float32(np.inf)

    def axis(dx, dy):
        best = np.full((h, w), big, np.float32)
        for s in (-1, 1):
            shifted = np.full_like(pos, np.nan)
            ys = slice(max(0, s * dy), h + min(0, s * dy))
            yd = slice(max(0, -s * dy), h + min(0, -s * dy))
            xs = slice(max(0, s * dx), w + min(0, s * dx))
            xd = slice(max(0, -s * dx), w + min(0, -s * dx))
            shifted[yd, xd] = pos[ys, xs]
            d = np.sqrt(_dist2(pos, shifted)).astype(np.float32)
            valid = np.isfinite(shifted).all(-1)
            best = np.where(valid & (d < best), d, best)
        return np.where(np.isfinite(best), best, np.float32(0))

    return np.maximum(axis(1, 0), axis(0, 1)).astype(np.float32)
