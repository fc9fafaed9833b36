# SPDX-License-Identifier: Apache-2.0
"""WSKPN: weight-sharing kernel prediction (Fan, Wang, Yang, Huo, Zheng, Bao, Wang; EGSR / CGF
2021), as implemented by afn. C++ inference: lib/core/methods/wskpn/ (the folded network).

From the paper and its public code: 6 RepVGG-style blocks (5x5 + 3x3 + 1x1 branches, identity in
blocks 2-5), width 14, leaky ReLU 0.1, folded into single 5x5 convolutions for inference; a head of
12 channels = 6 per-pixel weights (exp) + 6 fusion weights (softmax); filtering with 6 box windows
3, 5, ..., 13 where the weight belongs to the neighbour q and is shared by every centre pixel p:
``out_i(p) = sum_q w_i(q) x(q) / sum_q w_i(q)`` over the i-th window around p; the 6 results fused
by the softmax weights; remodulated by albedo; SMAPE loss (eps 0.01).

Chosen here (the paper leaves it open):

* Input: :mod:`afn.baselines.inputs` (T(cta), albedo, normal01, depth01; 10 channels); the boxes
  filter the linear HDR TA-1spp colour cta.
* Blocks: block 1 is 10 -> 14 and block 6 is 14 -> 12 (the head: no activation, no identity);
  blocks 2-5 are 14 -> 14 with identity; leaky ReLU 0.1 after blocks 1-5. No batch normalisation
  in the branches (the folding is then an exact sum; the official code's BN only matters for
  training stability at batch 64 on a GPU).
* Folding (:meth:`WSKPN.folded_state`): W5 + pad(W3, 1) + pad(W1, 2) + identity at the centre tap,
  biases summed; the C++ engine runs only the folded 5x5 layers ``conv1`` ... ``conv6``.
* Weights: ``w_i = exp(clamp(logit_i, -20, 20))`` (the clamp keeps exp finite in float32; a
  window sum of 169 weights <= 169 e^20 cannot overflow).
* Borders: windows are cut at the image edge (zero padding of both sums), so a border pixel
  averages only the pixels inside the image. A window whose weight sum is below 1e-30 (cannot
  happen with the clamp) gives 0.
* Fusion: softmax over the 6 fusion logits (max subtracted).

Cost (from :func:`cost_per_pixel`, FLOP = 2 per multiply-add, folded network): convolutions
54,600 FLOP, filtering ~204 FLOP per pixel; 27,382 parameters folded (38,466 while training).
"""

import torch
import torch.nn.functional as F
from torch import nn

from .inputs import INPUT_CHANNELS, network_input

WIDTH = 14
BLOCKS = 6
WINDOWS = (3, 5, 7, 9, 11, 13)
HEAD_CHANNELS = 2 * len(WINDOWS)   # 6 weight logits, then 6 fusion logits
LOGIT_CLAMP = 20.0
SUM_EPS = 1e-30
SMAPE_EPS = 0.01
LEAKY_SLOPE = 0.1


class RepBlock(nn.Module):
    """5x5 + 3x3 + 1x1 convolution branches (+ identity), summed."""

    def __init__(self, cin, cout, identity):
        super().__init__()
        self.b5 = nn.Conv2d(cin, cout, 5, padding=2)
        self.b3 = nn.Conv2d(cin, cout, 3, padding=1)
        self.b1 = nn.Conv2d(cin, cout, 1)
        self.identity = identity and cin == cout

    def forward(self, x):
        y = self.b5(x) + self.b3(x) + self.b1(x)
        return y + x if self.identity else y

    def folded(self):
        """(weight (cout, cin, 5, 5), bias (cout)) of the one 5x5 conv equal to this block."""
        w = self.b5.weight.detach().clone()
        w += F.pad(self.b3.weight.detach(), (1, 1, 1, 1))
        w += F.pad(self.b1.weight.detach(), (2, 2, 2, 2))
        if self.identity:
            for c in range(w.shape[0]):
                w[c, c, 2, 2] += 1.0
        b = self.b5.bias.detach() + self.b3.bias.detach() + self.b1.bias.detach()
        return w, b


def box_sum(x, k):
    """Sum over the k x k window around each pixel (zero outside the image); (B, C, H, W)."""
    return F.avg_pool2d(x, k, stride=1, padding=k // 2, count_include_pad=True) * float(k * k)


def filter_and_fuse(color, head):
    """WSKPN's weight-sharing filtering.

    Args:
        color: (B, 3, H, W) linear HDR demodulated colour.
        head: (B, 12, H, W) network head: weight logits (6), fusion logits (6).

    Returns:
        (B, 3, H, W) fused filtered colour.
    """
    n = len(WINDOWS)
    w = torch.exp(torch.clamp(head[:, :n], -LOGIT_CLAMP, LOGIT_CLAMP))
    fusion = torch.softmax(head[:, n:], 1)
    out = torch.zeros_like(color)
    for i, k in enumerate(WINDOWS):
        wi = w[:, i:i + 1]
        num = box_sum(wi * color, k)
        den = box_sum(wi, k)
        filt = torch.where(den > SUM_EPS, num / den.clamp_min(SUM_EPS), torch.zeros_like(num))
        out = out + fusion[:, i:i + 1] * filt
    return out


class WSKPN(nn.Module):
    """The training-time network (RepVGG branches); :meth:`folded_state` gives the inference one.

    Example:
        >>> net = WSKPN()
        >>> o = net(cta, albedo, normal01, depth01)["o"]  # demodulated; color.remodulate after
    """

    def __init__(self):
        super().__init__()
        widths = [INPUT_CHANNELS] + [WIDTH] * (BLOCKS - 1) + [HEAD_CHANNELS]
        self.blocks = nn.ModuleList(
            RepBlock(widths[i], widths[i + 1], identity=0 < i < BLOCKS - 1) for i in range(BLOCKS))

    def head(self, x):
        for i, b in enumerate(self.blocks):
            x = b(x)
            if i < BLOCKS - 1:
                x = F.leaky_relu(x, LEAKY_SLOPE)
        return x

    def forward(self, cta, albedo, normal01, depth01):
        """Inputs (B, C, H, W) as afn's (cta linear HDR demodulated); returns {"o", "head"}."""
        head = self.head(network_input(cta, albedo, normal01, depth01))
        return {"o": filter_and_fuse(cta, head), "head": head}

    def folded_state(self):
        """{"conv1.weight", "conv1.bias", ..., "conv6.*"}: the 6 folded 5x5 layers."""
        out = {}
        for i, b in enumerate(self.blocks):
            w, bias = b.folded()
            out[f"conv{i + 1}.weight"] = w
            out[f"conv{i + 1}.bias"] = bias
        return out


class FoldedWSKPN(nn.Module):
    """The inference network: 6 plain 5x5 convs (what the C++ engine runs)."""

    def __init__(self, state):
        super().__init__()
        self.convs = nn.ModuleList()
        for i in range(BLOCKS):
            w = state[f"conv{i + 1}.weight"]
            c = nn.Conv2d(w.shape[1], w.shape[0], 5, padding=2)
            c.weight.data.copy_(torch.as_tensor(w))
            c.bias.data.copy_(torch.as_tensor(state[f"conv{i + 1}.bias"]))
            self.convs.append(c)

    def forward(self, cta, albedo, normal01, depth01):
        x = network_input(cta, albedo, normal01, depth01)
        for i, c in enumerate(self.convs):
            x = c(x)
            if i < BLOCKS - 1:
                x = F.leaky_relu(x, LEAKY_SLOPE)
        return {"o": filter_and_fuse(cta, x), "head": x}


def loss(output, target):
    """SMAPE with the paper's eps 0.01 on the remodulated output (linear HDR)."""
    return torch.mean(torch.abs(output - target) / (output.abs() + target.abs() + SMAPE_EPS))


def cost_per_pixel():
    """FLOP per pixel (2 per multiply-add) of the folded network and the filtering; parameters."""
    widths = [INPUT_CHANNELS] + [WIDTH] * (BLOCKS - 1) + [HEAD_CHANNELS]
    conv = sum(2 * 25 * widths[i] * widths[i + 1] for i in range(BLOCKS))
    # Per window: w*x (3 mul), separable box sums of 4 channels (2 x 4 adds x 2 passes), divide 3,
    # fuse 3 FMAs (6); plus exp/softmax of 12 logits (~3 each).
    filt = len(WINDOWS) * (3 + 16 + 3 + 6) + 12 * 3
    folded = sum(widths[i] * widths[i + 1] * 25 + widths[i + 1] for i in range(BLOCKS))
    training = sum(p.numel() for p in WSKPN().parameters())
    return {"network": conv, "filtering": filt, "total": conv + filt, "parameters": folded,
            "training_parameters": training}
