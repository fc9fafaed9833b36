# SPDX-License-Identifier: Apache-2.0
"""Shared pieces of the learned baselines (ONND, MR-KP).

Inputs (the shared protocol of the NBGD/WSKPN/MR-KP papers, shared/reference): the network sees
10 channels ``[T(cta), albedo, normal01, depth01]`` where ``cta`` is the afn method's TA-1spp
demodulated colour (the same ``afntool --features`` the AFN model trains on, dataset.py) and
``T(x) = clip(max(x, 0)^(1/2.2), 0, 1)``; the output is demodulated irradiance, remodulated by
the albedo (color.remodulate) as afn does. The C++ methods (lib/core/methods/onnd, mrkp) compute
the same features with the same shared stages.
"""

import numpy as np
import torch
import torch.nn.functional as F

from ..color import tonemap

INPUT_CHANNELS = 10     # T(cta) 3, albedo 3, normal01 3, depth01 1
SEQ_KEYS = ("cta", "albedo", "normal01", "depth01", "target")


def network_input(cta, albedo, normal01, depth01):
    """(B, 10, H, W) network input from the feature tensors (each (B, C, H, W))."""
    return torch.cat([tonemap(cta), albedo, normal01, depth01], 1)


def pad_to_multiple(x, m):
    """Replicate-pad (B, C, H, W) at the right and bottom to multiples of m (as afn's model)."""
    h, w = x.shape[-2:]
    ph, pw = (-h) % m, (-w) % m
    if ph == 0 and pw == 0:
        return x
    return F.pad(x, (0, pw, 0, ph), mode="replicate")


def up2(x):
    """Nearest 2x upsampling."""
    return F.interpolate(x, scale_factor=2, mode="nearest")


def count_parameters(model):
    return sum(p.numel() for p in model.parameters())


class SequenceSampler:
    """Random training crops of whole sequences: the same window in every frame of a scene, with
    the same random flips and brightness gain in [0.8, 1.2] (dataset.CropSampler's augmentation,
    applied per sequence so the recurrent ONND sees a consistent clip)."""

    def __init__(self, scenes, crop=64, frames=6, seed=0):
        self.scenes = list(scenes)
        self.crop = crop
        self.frames = frames
        self.rng = np.random.RandomState(seed)

    def sample(self):
        s = self.scenes[self.rng.randint(len(self.scenes))]
        n, h, w = s["cta"].shape[:3]
        t = min(self.frames, n)
        f0 = self.rng.randint(n - t + 1)
        y = self.rng.randint(max(h - self.crop, 0) + 1)
        x = self.rng.randint(max(w - self.crop, 0) + 1)
        out = {k: s[k][f0:f0 + t, y:y + self.crop, x:x + self.crop] for k in SEQ_KEYS}
        if self.rng.rand() < 0.5:
            out = {k: v[:, :, ::-1] for k, v in out.items()}
        if self.rng.rand() < 0.5:
            out = {k: v[:, ::-1] for k, v in out.items()}
        gain = np.float32(self.rng.uniform(0.8, 1.2))
        for k in ("cta", "target"):
            out[k] = out[k] * gain
        return {k: np.ascontiguousarray(v, np.float32) for k, v in out.items()}

    def batch(self, n):
        """dict key -> (T, B, C, H, W) tensor."""
        items = [self.sample() for _ in range(n)]
        return {k: torch.from_numpy(np.stack([it[k] for it in items], 1)).permute(0, 1, 4, 2, 3)
                .contiguous() for k in SEQ_KEYS}
