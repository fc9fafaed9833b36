# SPDX-License-Identifier: Apache-2.0
"""SMAPE loss, Eq. 5 of Lee et al. (after Vogels et al. 2018)."""

import torch

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
