# SPDX-License-Identifier: Apache-2.0
"""MR-KP: multi-resolution kernel prediction as defined in the NBGD paper's supplement (KPCN,
Bako et al. 2017, made multi-resolution with Vogels et al. 2018's level blending), as afn's
baseline. The C++ engine (lib/core/methods/mrkp/network.cpp) implements exactly this graph;
parameter names are the tensor names of the .afnw archive.

From the papers: 5-level encoder of 3x3 convs with ReLU and 2x2 average pooling; a decoder of
stride-2 transposed convs with skips; heads of 26 channels (a 5x5 kernel and a blend weight) at
full, 1/2 and 1/4 resolution; kernel weights ReLU'd and normalised by their sum + 1e-8; levels
combined as ``d - alpha * U(D(d)) + alpha * U(coarser)``; L1 on the tone-mapped output.

Chosen here (the papers are open or our budget differs; see also common.py):

* Width 32 instead of 48 and one 3x3 conv per level (CPU training budget, < 1 MB of weights):
  ``e0 = relu(conv(x))`` (full), ``e_l = relu(conv(avgpool(e_{l-1})))`` for l = 1..4 (1/16).
* Decoder: 2x2 stride-2 transposed convs (the reference code's 3x3 stride-2 transposed conv has
  output-padding choices; 2x2 stride 2 is the exact inverse of the pooling grid):
  ``y_4 = e_4``; ``y_l = relu(conv([relu(convT(y_{l+1})), e_l]))``.
* Heads: 1x1 convs on y_0, y_1, y_2 -> 26 channels: 25 kernel logits (tap j = (dy+2)*5 +
  (dx+2)) and the blend logit; alpha = sigmoid (level 0 and 1; level 2 has no coarser level, its
  alpha channel is unused but kept for a uniform head).
* Filtered images: d_0 = cta (HDR, demodulated), d_1 = avgpool(d_0), d_2 = avgpool(d_1);
  ``f_l = sum_j relu(k_j) * d_l(p + o_j) / (sum_j relu(k_j) + 1e-8)`` with replicate padding at
  the image border. ``o_2 = f_2``, ``o_l = f_l - a_l * U(D(f_l)) + a_l * U(o_{l+1})`` with D =
  2x2 average pooling and U = nearest 2x upsampling (as afn's fusion).
* Inputs replicate-padded to a multiple of 16, output cropped.
"""

import torch
import torch.nn.functional as F
from torch import nn

from ..color import tonemap, remodulate
from .common import INPUT_CHANNELS, network_input, pad_to_multiple, up2

WIDTH = 32
LEVELS = 5
KERNEL = 5
TAPS = KERNEL * KERNEL
HEAD = TAPS + 1
FILTER_LEVELS = 3
PAD_MULTIPLE = 16
KERNEL_EPS = 1e-8


def apply_kernel(img, logits):
    """``sum_j relu(k_j) img(p + o_j) / (sum_j relu(k_j) + eps)``, replicate border."""
    k = F.relu(logits[:, :TAPS])
    r = KERNEL // 2
    h, w = img.shape[-2:]
    padded = F.pad(img, (r, r, r, r), mode="replicate")
    acc = torch.zeros_like(img)
    for j in range(TAPS):
        dy, dx = j // KERNEL, j % KERNEL
        acc = acc + k[:, j:j + 1] * padded[:, :, dy:dy + h, dx:dx + w]
    return acc / (k.sum(1, keepdim=True) + KERNEL_EPS)


class MRKP(nn.Module):
    def __init__(self, width=WIDTH):
        super().__init__()
        self.width = width
        self.enc0 = nn.Conv2d(INPUT_CHANNELS, width, 3, padding=1)
        for l in range(1, LEVELS):
            setattr(self, f"enc{l}", nn.Conv2d(width, width, 3, padding=1))
        for l in range(LEVELS - 1):
            setattr(self, f"up{l}", nn.ConvTranspose2d(width, width, 2, stride=2))
            setattr(self, f"dec{l}", nn.Conv2d(2 * width, width, 3, padding=1))
        for l in range(FILTER_LEVELS):
            head = nn.Conv2d(width, HEAD, 1)
            with torch.no_grad():
                head.bias[:TAPS].fill_(0.5)   # start near a box filter, not dead ReLUs
            setattr(self, f"head{l}", head)

    def forward(self, cta, albedo, normal01, depth01):
        """Demodulated irradiance (B, 3, H, W) from the features (common.py)."""
        h, w = cta.shape[-2:]
        feats = [pad_to_multiple(t, PAD_MULTIPLE) for t in (cta, albedo, normal01, depth01)]
        x = network_input(*feats)
        e = [F.relu(self.enc0(x))]
        for l in range(1, LEVELS):
            e.append(F.relu(getattr(self, f"enc{l}")(F.avg_pool2d(e[-1], 2))))
        y = e[-1]
        dec = [None] * LEVELS
        for l in reversed(range(LEVELS - 1)):
            u = F.relu(getattr(self, f"up{l}")(y))
            y = F.relu(getattr(self, f"dec{l}")(torch.cat([u, e[l]], 1)))
            dec[l] = y
        d = [feats[0]]
        for _ in range(1, FILTER_LEVELS):
            d.append(F.avg_pool2d(d[-1], 2))
        o = None
        for l in reversed(range(FILTER_LEVELS)):
            head = getattr(self, f"head{l}")(dec[l])
            f = apply_kernel(d[l], head)
            if o is None:
                o = f
            else:
                a = torch.sigmoid(head[:, TAPS:])
                o = f - a * up2(F.avg_pool2d(f, 2)) + a * up2(o)
        return o[..., :h, :w]


def loss(model, batch):
    """L1 on the tone-mapped remodulated output (one frame per item; batch (B, C, H, W))."""
    irr = model(batch["cta"], batch["albedo"], batch["normal01"], batch["depth01"])
    o = tonemap(remodulate(irr, batch["albedo"]))
    return torch.mean(torch.abs(o - tonemap(batch["target"])))


def cost_per_pixel(model):
    """FLOP per full-resolution pixel (2 per multiply-add; filtering 2 per tap and channel plus
    the weight sum) and parameter count."""
    w = model.width
    flop = 2 * 9 * INPUT_CHANNELS * w
    flop += sum(2 * 9 * w * w / 4 ** l for l in range(1, LEVELS))
    flop += sum((2 * 4 * w * w + 2 * 9 * 2 * w * w) / 4 ** l for l in range(LEVELS - 1))
    flop += sum((2 * w * HEAD + TAPS * (2 * 3 + 2) + 12) / 4 ** l for l in range(FILTER_LEVELS))
    return {"flop_per_pixel": flop, "parameters": sum(p.numel() for p in model.parameters())}
