# SPDX-License-Identifier: Apache-2.0
"""Colour and feature transforms shared by the network, the dataset and the C++ core.

The C++ core (lib/core/stages/feature_scaling.cpp, lib/core/stages/demodulate.h) uses the same
constants; they are kept in agreement by the parity test (tests/data/afn_parity) and
tests/unit/test_afn_*.cpp.

Conventions:
  * tone map for network inputs (NBGD/WSKPN, Lee et al. Sec. III-A):
    ``T(x) = clip(max(x, 0) ** (1 / 2.2), 0, 1)``
  * demodulation (lib/core/stages/demodulate.h): ``irr = colour / max(albedo, ALBEDO_EPS)``, remodulation
    ``colour = irr * max(albedo, ALBEDO_EPS)``; ALBEDO_EPS = 2^-10. ``albedo`` is the dataset's
    "albedo" feature: the demodulation factor after the core's aux prefilter
    (lib/core/stages/aux_prefilter.h), so training remodulates exactly as the C++ filter does.
  * shading normal to [0, 1]: ``clip(n * 0.5 + 0.5, 0, 1)``.
  * depth to [0, 1]: per-frame min-max over finite values below DEPTH_SKY (WSKPN); values that are
    non-finite or >= DEPTH_SKY (Blender writes 1e10 for the sky) map to 1 (far).
"""

import numpy as np
import torch

GAMMA = 2.2                     # tone-map exponent 1 / GAMMA
ALBEDO_EPS = 1.0 / 1024.0       # floor of the albedo divisor, lib/core/stages/demodulate.h kAlbedoEpsilon
MAX_IRRADIANCE = 1e15           # lib/core/stages/demodulate.h kMaxIrradiance
DEPTH_SKY = 1e9                 # depth at or beyond this is "no surface" (Blender sky: 1e10)


def tonemap(x: torch.Tensor) -> torch.Tensor:
    """Tone map linear HDR to the network's LDR input.

    Args:
        x: (..., H, W) linear HDR, any sign.

    Returns:
        Same shape, in [0, 1]: ``clip(max(x, 0) ** (1/2.2), 0, 1)``.
    """
    return _Tonemap.apply(x)


TONEMAP_GRAD_FLOOR = 1e-4       # the derivative of x^(1/2.2) is taken at max(x, this) (see below)


class _Tonemap(torch.autograd.Function):
    """T(x) with the exact forward value and a bounded derivative.

    The plain composition clamp -> pow -> clamp has an infinite derivative at x = 0 and turns it
    into NaN (inf * 0) for x <= 0; the refinement input T(i) depends on the network, so one such
    pixel poisons the whole gradient. Here dT/dx = x_f^(1/2.2 - 1) / 2.2 with x_f = max(x, 1e-4)
    for 0 < x < 1 (at most ~68), and 0 elsewhere, the forward value is unchanged (C++ parity).
    """

    @staticmethod
    def forward(ctx, x):
        ctx.save_for_backward(x)
        return torch.clamp(torch.clamp(x, min=0.0) ** (1.0 / GAMMA), 0.0, 1.0)

    @staticmethod
    def backward(ctx, grad):
        (x,) = ctx.saved_tensors
        xf = torch.clamp(x, min=TONEMAP_GRAD_FLOOR)
        d = xf ** (1.0 / GAMMA - 1.0) / GAMMA
        return grad * torch.where((x > 0) & (x < 1), d, torch.zeros_like(d))


def demodulate(color: np.ndarray, albedo: np.ndarray) -> np.ndarray:
    """Divide colour by the floored albedo (numpy, float32, (..., 3)); clamp to [0, MAX]."""
    irr = color / np.maximum(albedo, ALBEDO_EPS)
    irr = np.where(np.isfinite(irr), irr, 0.0)
    return np.clip(irr, 0.0, MAX_IRRADIANCE).astype(np.float32)


def remodulate(irr, albedo):
    """Multiply by the floored albedo (numpy array or torch tensor)."""
    if isinstance(irr, torch.Tensor):
        return irr * torch.clamp(albedo, min=ALBEDO_EPS)
    return irr * np.maximum(albedo, ALBEDO_EPS)


def normal_to_unit_range(n: np.ndarray) -> np.ndarray:
    """Shading normal in [-1, 1] to [0, 1] (non-finite -> 0.5)."""
    n = np.where(np.isfinite(n), n, 0.0)
    return np.clip(n * 0.5 + 0.5, 0.0, 1.0).astype(np.float32)


def depth_to_unit_range(z: np.ndarray) -> np.ndarray:
    """Per-frame min-max of the valid depth values to [0, 1]; invalid -> 1; constant -> 0."""
    finite = np.isfinite(z) & (np.abs(z) < DEPTH_SKY)
    if not finite.any():
        return np.ones_like(z, dtype=np.float32)
    lo, hi = float(z[finite].min()), float(z[finite].max())
    scale = 1.0 / (hi - lo) if hi > lo else 0.0
    out = np.where(finite, (z - lo) * scale, 1.0)
    return np.clip(out, 0.0, 1.0).astype(np.float32)
