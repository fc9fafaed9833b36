# SPDX-License-Identifier: Apache-2.0
"""Per-pixel kernel filtering (Eq. 2) over a padded image, with a hand-written backward.

``out[b, c, y, x] = sum_j kernels[b, j, y, x] * padded[b, c, y + dy_j, x + dx_j]`` for the
size x size taps j = dy * size + dx (F.unfold order). The forward is the same sum of shifted
slices the models always used (so its values and the C++ parity are unchanged); what differs is
the backward. Built from autograd's slices, every tap's backward allocated a zero tensor the size
of the padded image and added it in (``SliceBackward``): 98 full-frame fills and adds per step of
AFN, 81 % of a training step's CPU time (torch.profiler, 2026-12-03). Here the gradient of the
padded image is one buffer the taps accumulate into in place, and the kernels' gradient is one
channel sum per tap.
"""

import torch


class _ShiftedFilter(torch.autograd.Function):
    @staticmethod
    def forward(ctx, padded, kernels, size):
        h, w = padded.shape[-2] - size + 1, padded.shape[-1] - size + 1
        out = padded.new_zeros(padded.shape[0], padded.shape[1], h, w)
        for j in range(size * size):
            dy, dx = divmod(j, size)
            out.addcmul_(kernels[:, j:j + 1], padded[:, :, dy:dy + h, dx:dx + w])
        ctx.save_for_backward(padded, kernels)
        ctx.size = size
        return out

    @staticmethod
    def backward(ctx, grad):
        padded, kernels = ctx.saved_tensors
        size = ctx.size
        h, w = grad.shape[-2:]
        grad = grad.contiguous()
        grad_padded = torch.zeros_like(padded) if ctx.needs_input_grad[0] else None
        grad_kernels = torch.empty_like(kernels) if ctx.needs_input_grad[1] else None
        for j in range(size * size):
            dy, dx = divmod(j, size)
            if grad_kernels is not None:
                window = padded[:, :, dy:dy + h, dx:dx + w]
                torch.sum(grad * window, dim=1, out=grad_kernels[:, j])
            if grad_padded is not None:
                grad_padded[:, :, dy:dy + h, dx:dx + w].addcmul_(kernels[:, j:j + 1], grad)
        return grad_padded, grad_kernels, None


def shifted_filter(padded: torch.Tensor, kernels: torch.Tensor, size: int) -> torch.Tensor:
    """Filter ``padded`` (B, C, H + size - 1, W + size - 1) with per-pixel kernels (B, size^2, H, W).

    Returns (B, C, H, W). Differentiable in both arguments (first-order gradients only).
    """
    if padded.shape[-2] - size + 1 != kernels.shape[-2] or \
            padded.shape[-1] - size + 1 != kernels.shape[-1] or kernels.shape[1] != size * size:
        raise ValueError(f"shifted_filter: image {tuple(padded.shape)} and kernels "
                         f"{tuple(kernels.shape)} do not match a {size}x{size} filter")
    return _ShiftedFilter.apply(padded, kernels.contiguous(), size)
