# SPDX-License-Identifier: Apache-2.0
"""ONND: the recurrent denoising autoencoder of Chaitanya et al. 2017 (OptiX's ancestor), as
afn's baseline. The C++ engine (lib/core/methods/onnd/network.cpp) implements exactly this graph;
parameter names are the tensor names of the .afnw archive.

From the paper: U-Net of 3x3 convolutions with leaky ReLU 0.1; 2x2 max-pooling between encoder
levels; per encoder level a recurrent block of three 3x3 convs, the second reading the same
level's previous-frame output concatenated (not warped); nearest upsampling and skip
concatenation in the decoder; widths growing ~4/3 per level; loss 0.8 L1 + 0.1 HFEN (LoG 9x9,
sigma 1.5) + 0.1 temporal L1 over sequences with increasing per-frame weights.

Chosen here (the paper is open or our budget differs; see also common.py):

* Inputs: the shared 10-channel protocol [T(cta), albedo, normal01, depth01] (common.py); the
  paper fed raw 1-spp colour and relied on the recurrence alone.
* Widths: half the paper's (16, 16, 22, 29, 38, 51, 51) minus the innermost level: recurrent
  encoder levels ``enc`` = (16, 22, 29, 38) at 1, 1/2, 1/4, 1/8 and a 2-conv bottleneck of 51 at
  1/16 (CPU training budget and < 1 MB of weights); inputs are replicate-padded to a multiple of
  2^levels (16) and the output cropped.
* Recurrent block per level l: ``a = lrelu(conv_a(x))``, ``b = lrelu(conv_b([a, h_prev]))``,
  ``h = lrelu(conv_c(b))``; h is the level's state for the next frame (zero on the first frame
  of a history) and its skip; the next level reads maxpool(h).
* Decoder level l: ``y = lrelu(conv1([up(y_{l+1}), h_l]))``, ``y = lrelu(conv2(y))``, width of
  the encoder level; then ``out = conv(y_0) -> 3`` (the paper's last 128, 64 widths dropped).
* Output: a log-domain residual on the input colour, ``net = exp(min(log1p(c) + out, 20)) - 1``
  with ``c = max(cta, 0)`` (so a short CPU training starts from the TA frame instead of black),
  blended with the input colour by a local-contrast gate computed from the input alone:
  irradiance ``= c + g * (net - c)``, ``g = min(1, GATE_GAIN * max_ch (hi - lo) / (hi + lo +
  GATE_EPS))`` with hi, lo the maximum and minimum of c over the 3x3 window (edges replicated).
  Why: the stress properties (tests/stress: a constant frame stays constant, black stays black,
  a static scene reaches a fixed point) must hold by construction, not by training. On a flat
  window hi == lo exactly in floating point, so g == 0 and the output is the input colour
  bit for bit, whatever the network and its recurrent state say; black is the flat case c == 0.
  A max/min contrast rather than a standard deviation because a mean of equal floats need not
  equal them (the deviation would be tiny but not zero). The gain 8 opens the gate fully at
  hi/lo ~ 1.29, far below the contrast of 1-spp noise, so noisy pixels see the plain network.
  A purely multiplicative output (``c * exp(out)``) was rejected: it cannot brighten a pixel
  whose TA colour is exactly zero, which 1-spp frames have in every dark region.
* Sequences: the dataset has 6 frames per sequence; the paper's 7 temporal weights are used
  from the second on: 0.044, 0.135, 0.325, 0.607, 0.882, 1.0. Losses on the tone-mapped
  remodulated output T(o) against T(reference).
"""

import math

import torch
import torch.nn.functional as F
from torch import nn

from ..color import remodulate, tonemap
from .common import INPUT_CHANNELS, network_input, pad_to_multiple, up2

ENC = (16, 22, 29, 38)
BOTTLENECK = 51
LEAK = 0.1
LOG_CLAMP = 20.0
GATE_RADIUS = 1      # 3x3 window of the contrast gate
GATE_GAIN = 8.0
GATE_EPS = 1e-4      # keeps the ratio finite at black; dark noise (1e-3 vs 0) still opens it
FRAME_WEIGHTS = (0.011, 0.044, 0.135, 0.325, 0.607, 0.882, 1.0)


def _conv3(cin, cout):
    return nn.Conv2d(cin, cout, 3, padding=1)


def lrelu(x):
    return F.leaky_relu(x, LEAK)


def contrast_gate(c):
    """(B, 1, H, W) gate in [0, 1] from the colour c = max(cta, 0) (B, 3, H, W); exactly 0
    wherever the 3x3 window (edges replicated) is flat (module docstring)."""
    r = GATE_RADIUS
    p = F.pad(c, (r, r, r, r), mode="replicate")
    hi = F.max_pool2d(p, 2 * r + 1, stride=1)
    lo = -F.max_pool2d(-p, 2 * r + 1, stride=1)
    contrast = (hi - lo) / (hi + lo + GATE_EPS)
    return torch.clamp(GATE_GAIN * contrast.amax(1, keepdim=True), max=1.0)


class ONND(nn.Module):
    """Recurrent U-Net; ``forward`` denoises one frame given the previous frame's states."""

    def __init__(self, enc=ENC, bottleneck=BOTTLENECK):
        super().__init__()
        self.enc = tuple(enc)
        self.bottleneck = bottleneck
        self.pad_multiple = 2 ** len(self.enc)   # every pooling level exact
        cin = INPUT_CHANNELS
        for l, w in enumerate(self.enc):
            setattr(self, f"enc{l}a", _conv3(cin, w))
            setattr(self, f"enc{l}b", _conv3(2 * w, w))
            setattr(self, f"enc{l}c", _conv3(w, w))
            cin = w
        self.bott1 = _conv3(cin, bottleneck)
        self.bott2 = _conv3(bottleneck, bottleneck)
        below = bottleneck
        for l in reversed(range(len(self.enc))):
            w = self.enc[l]
            setattr(self, f"dec{l}a", _conv3(below + w, w))
            setattr(self, f"dec{l}b", _conv3(w, w))
            below = w
        self.out = _conv3(self.enc[0], 3)

    def forward(self, cta, albedo, normal01, depth01, state=None):
        """One frame.

        Args:
            cta, albedo, normal01, depth01: (B, C, H, W) features (common.py).
            state: list of the previous frame's per-level states (padded size), or None.

        Returns:
            (irradiance (B, 3, H, W) demodulated, new state list).
        """
        h, w = cta.shape[-2:]
        feats = [pad_to_multiple(t, self.pad_multiple) for t in (cta, albedo, normal01, depth01)]
        x = network_input(*feats)
        skips = []
        for l in range(len(self.enc)):
            a = lrelu(getattr(self, f"enc{l}a")(x))
            prev = state[l] if state is not None else torch.zeros_like(a)
            b = lrelu(getattr(self, f"enc{l}b")(torch.cat([a, prev], 1)))
            s = lrelu(getattr(self, f"enc{l}c")(b))
            skips.append(s)
            x = F.max_pool2d(s, 2)
        y = lrelu(self.bott2(lrelu(self.bott1(x))))
        for l in reversed(range(len(self.enc))):
            y = lrelu(getattr(self, f"dec{l}a")(torch.cat([up2(y), skips[l]], 1)))
            y = lrelu(getattr(self, f"dec{l}b")(y))
        c = torch.clamp(feats[0], min=0.0)
        net = torch.exp(torch.clamp(torch.log1p(c) + self.out(y), max=LOG_CLAMP)) - 1.0
        irr = c + contrast_gate(c) * (net - c)
        return irr[..., :h, :w], skips


def log_kernel(size=9, sigma=1.5):
    """(1, 1, size, size) Laplacian of Gaussian, zero mean (HFEN's filter)."""
    r = size // 2
    ax = torch.arange(-r, r + 1, dtype=torch.float32)
    yy, xx = torch.meshgrid(ax, ax, indexing="ij")
    r2 = (xx ** 2 + yy ** 2) / (2 * sigma ** 2)
    k = -(1.0 - r2) * torch.exp(-r2) / (math.pi * sigma ** 4)
    return (k - k.mean()).view(1, 1, size, size)


def hfen(a, b, kernel):
    """L1 of the LoG-filtered difference (per channel)."""
    c = a.shape[1]
    k = kernel.to(a).expand(c, 1, -1, -1)
    return torch.mean(torch.abs(F.conv2d(a - b, k, padding=kernel.shape[-1] // 2, groups=c)))


def sequence_loss(model, seq, kernel):
    """Weighted ONND loss over a (T, B, C, H, W) batch of sequences (module docstring)."""
    t_count = seq["cta"].shape[0]
    weights = FRAME_WEIGHTS[-t_count:]
    state, prev_o, prev_t, total = None, None, None, 0.0
    for t in range(t_count):
        irr, state = model(seq["cta"][t], seq["albedo"][t], seq["normal01"][t],
                           seq["depth01"][t], state)
        o = tonemap(remodulate(irr, seq["albedo"][t]))
        ref = tonemap(seq["target"][t])
        loss = 0.8 * torch.mean(torch.abs(o - ref)) + 0.1 * hfen(o, ref, kernel)
        if prev_o is not None:
            loss = loss + 0.1 * torch.mean(torch.abs((o - prev_o) - (ref - prev_t)))
        total = total + weights[t] * loss
        prev_o, prev_t = o, ref
    return total / sum(weights)


def cost_per_pixel(model):
    """FLOP per full-resolution pixel (2 per multiply-add) and parameter count."""
    flop = 0.0
    for name, m in model.named_modules():
        if isinstance(m, nn.Conv2d):
            level = int(name[3]) if name[:3] in ("enc", "dec") else (
                len(model.enc) if name.startswith("bott") else 0)
            flop += 2 * m.in_channels * m.out_channels * 9 / 4 ** level
    return {"flop_per_pixel": flop, "parameters": sum(p.numel() for p in model.parameters())}
