# SPDX-License-Identifier: Apache-2.0
"""shifted_filter: the hand-written backward against autograd through shifted slices."""

import os
import sys

import pytest
import torch

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from afn.shifted_filter import shifted_filter  # noqa: E402


def slices_reference(padded, kernels, size):
    h, w = kernels.shape[-2:]
    out = torch.zeros(padded.shape[0], padded.shape[1], h, w, dtype=padded.dtype)
    for j in range(size * size):
        dy, dx = divmod(j, size)
        out = out + kernels[:, j:j + 1] * padded[:, :, dy:dy + h, dx:dx + w]
    return out


@pytest.mark.parametrize("size", [3, 5, 7])
def test_values_and_gradients_match_autograd_through_slices(size):
    g = torch.Generator().manual_seed(size)
    padded = torch.randn(2, 3, 9 + size - 1, 11 + size - 1, generator=g, dtype=torch.float64)
    kernels = torch.randn(2, size * size, 9, 11, generator=g, dtype=torch.float64)
    upstream = torch.randn(2, 3, 9, 11, generator=g, dtype=torch.float64)
    a = [t.clone().requires_grad_() for t in (padded, kernels)]
    b = [t.clone().requires_grad_() for t in (padded, kernels)]
    out = shifted_filter(a[0], a[1], size)
    ref = slices_reference(b[0], b[1], size)
    assert torch.allclose(out, ref, rtol=0, atol=1e-12)
    (out * upstream).sum().backward()
    (ref * upstream).sum().backward()
    assert torch.allclose(a[0].grad, b[0].grad, rtol=0, atol=1e-12)   # every tap's shift
    assert torch.allclose(a[1].grad, b[1].grad, rtol=0, atol=1e-12)
    assert torch.autograd.gradcheck(lambda p, k: shifted_filter(p, k, size),
                                    (padded[:1, :2, :size + 3, :size + 4].clone().requires_grad_(),
                                     kernels[:1, :, :4, :5].clone().requires_grad_()))


def test_gradient_of_one_argument_only_and_shape_errors():
    padded = torch.randn(1, 3, 10, 10, requires_grad=True)
    kernels = torch.softmax(torch.randn(1, 49, 4, 4), 1)          # no gradient asked
    shifted_filter(padded, kernels, 7).sum().backward()
    # Each kernel sums to 1 and d(sum)/d(padded) counts how often a pixel is read, weighted.
    assert padded.grad is not None and padded.grad.sum().item() == pytest.approx(3 * 16, rel=1e-5)
    with pytest.raises(ValueError):
        shifted_filter(padded, torch.randn(1, 49, 5, 4), 7)
    with pytest.raises(ValueError):
        shifted_filter(padded, torch.randn(1, 25, 4, 4), 7)
