# SPDX-License-Identifier: Apache-2.0
"""SMAPE loss, Eq. 5 of Lee et al. (after Vogels et al. 2018)."""

import torch

from . import color

SMAPE_EPS = 1e-3   # epsilon of Eq. 5 (the paper's value)


def smape(output: torch.Tensor, target: torch.Tensor, eps: float = SMAPE_EPS) -> torch.Tensor:
    """Symmetric mean absolute percentage error.

    Args:
        output: (B, 3, H, W) remodulated output o' (linear HDR).
        target: (B, 3, H, W) reference radiance (linear HDR).
        eps: epsilon of the denominator.

    Returns:
        Scalar: ``mean(|o - t| / (|o| + |t| + eps))`` over batch, pixels and the 3 channels (1/3N).
    """
    return torch.mean(torch.abs(output - target) / (output.abs() + target.abs() + eps))


def temporal_gradient(output: torch.Tensor, target: torch.Tensor) -> torch.Tensor:
    """Temporal term: mean |(T(o_t) - T(o_t-1)) - (T(r_t) - T(r_t-1))| on the tone-mapped images
    (T as docs/metrics.md), the temporal-gradient error of the evaluation as a loss.

    Args:
        output, target: (2n, 3, H, W): n current frames, then their n previous frames
            (CropSampler.pair_batch).
    """
    n = output.shape[0] // 2
    to, tr = color.tonemap(output), color.tonemap(target)
    return torch.mean(torch.abs((to[:n] - to[n:]) - (tr[:n] - tr[n:])))
