# SPDX-License-Identifier: Apache-2.0
"""The Adaptive Fusion Network (Lee, Lee, Yoon, Song, "Real-Time Monte Carlo Denoising With
Adaptive Fusion Network", IEEE Access), Section III, as implemented by afn.

The C++ inference engine (lib/core/methods/afn/network.cpp) implements exactly this graph; the parameter
names (``enc1.weight`` ...) are the tensor names of the weights archive (weights.py).

Fixed by the paper: 7x7 per-pixel kernels (49 channels); K_TA applied at full resolution to the
TA-1spp frame, K_1spp at half resolution to the 2x average-pooled 1-spp frame; the filtering runs
on the HDR (non-tone-mapped) demodulated colour (Eq. 2); fusion Eq. 3
``i = d_TA - alpha * U(D(d_TA)) + alpha * U(d_1spp)`` with D = 2x2 average pooling and U = nearest
2x upsampling; refinement Eq. 4 ``o = i + R(i, f)``; output remodulated by albedo; SMAPE loss.

Chosen here (the paper leaves it open; see training/README.md and shared/reference/baselines.md):

* Network input x (13 ch, full res): T(r_1spp), T(r_TA), albedo, normal*0.5+0.5, depth01 with
  T(x) = clip(max(x,0)^(1/2.2), 0, 1) (color.py).
* Encoder-decoder M, starting at half resolution ("half-res-start U-Net"), 3x3 convs, ReLU:
  ``h = D(x)``; ``e1 = conv(h) 13->16`` (1/2); ``e2 = conv(D e1) 16->32`` (1/4);
  ``e3 = conv(D e2) 32->64`` (1/8); ``d2 = conv([U e3, e2]) 96->32`` (1/4);
  ``d1 = conv([U d2, e1]) 48->24`` (1/2).
* Heads (1x1 convs): ``K_1spp logits = head1(d1)`` 24->49 at 1/2;
  ``[K_TA logits, alpha logit] = headTA([U d1, x])`` 37->50 at full res (the full-res input
  features give the full-res kernels per-pixel detail without any full-res 3x3 conv).
* Kernels: softmax over the 49 taps (max subtracted); tap j = (dy+3)*7 + (dx+3) (F.unfold order),
  taps outside the (padded) image read 0 and are not renormalised. alpha = sigmoid(logit).
* Refinement R: ``[T(i), albedo, normal01, depth01]`` 10->16->16->3, 3x3 convs, ReLU between.
* Odd sizes: inputs are padded at the right/bottom to a multiple of 8 by edge replication
  (so every 2x pooling level is exact), the whole graph runs on the padded frame, and the output is
  cropped. The C++ engine does the same.
* Ablation variants (Table 11 of the paper): ``full`` (fusion + refinement), ``fusion`` (no
  refinement), ``1spp`` (the TA input is replaced by the 1-spp frame everywhere, no refinement),
  ``ta`` (the 1-spp input is replaced by the TA frame everywhere, no refinement).
* ``quarter`` (optional, not in the paper's graph): a third, quarter-resolution scale
  that widens the filter's footprint from 14 to 28 full-resolution pixels, fused like Eq. 3 but on
  the fused image: ``[K_q logits, beta logit] = head4(d2)`` 32->50 at 1/4;
  ``l = D(D(i))``; ``i <- i + U4(beta * (K_q * l - l))`` with U4 bilinear 4x upsampling
  (align_corners=False, edges clamped) so the swapped low band has no 4x4 blocks. It attacks
  the low-frequency blotches a 7x7 footprint on a few accumulated samples leaves (training/README,
  *The network*). ``head4`` starts near the identity: zero weights, the centre tap's logit
  bias QUARTER_CENTRE_LOGIT (its weight 0.89, the other 48 share 0.11) and beta 0.5, so a model
  grown from a trained one (``--init``) starts close to where it was (the low band blurred by
  about 5 %) while the kernels and beta both get useful gradients. (Uniform kernels with beta at
  sigmoid(-4) do not train: beta only falls, the blur it would bring being harmful before the
  kernels learn edges.)
* ``history`` (optional, not in the paper's graph): a 14th input channel ``history01`` = 1 / the
  frames the TA input holds at each pixel (1 where the accumulation was reset: disocclusion, a
  lighting change the history trust cut, the first frame; lib/core/methods/afn/network_inputs.h),
  appended to x, so ``enc1`` and ``headTA`` take one more input. The network can then tell a
  converged TA input from a one-frame one instead of guessing from its noise. A model grown from
  one without it (``widen.grow_history``) starts with zero weights there: the same output.
* ``albedo_trust`` (optional, not in the paper's graph): the learned albedo trust. The paper
  filters the albedo-demodulated colour and remodulates by the albedo, which is right where the
  albedo is clean and wrong where it is noise (glass, mirrors, metal seen through depth of field or
  motion blur: the renderer's albedo there is a per-pixel lottery, and dividing by it and
  multiplying by it again leaves dark and bright specks). Per pixel the network predicts
  ``t = sigmoid(headG(e1))`` (a 3x3 conv 16->1 on the first encoder level, half resolution,
  nearest-upsampled), the share of colour-space filtering, and the filtering runs on the colour
  demodulated by ``a' = a + (1 - a) * t`` instead of the albedo ``a``: ``t = 0`` is the paper's
  demodulation, ``t = 1`` filters the colour itself with the albedo and normal as guides only (as
  Open Image Denoise does). Both colour inputs are rescaled by
  ``s = max(a, eps) / max(a', eps)`` before the filtering (the 1-spp one before its pooling), the
  refinement runs in the same space, and the output is returned in the albedo-demodulated space
  (``o / s``) so the remodulation outside is unchanged and gives ``o * max(a', eps)``. Chosen over
  a second, colour-space filtering of the same kernels blended at the end: one filtering, the
  blend continuous per channel, and t is known before the filtering (from e1, whose rows every
  network stripe already computes with a wide halo). The network input x is unchanged (it sees
  the prefiltered albedo, lib/core/stages/aux_prefilter.h, as before). ``headG`` starts at zero
  weights and bias ALBEDO_TRUST_BIAS (t = 0.0025), so a model grown from a trained one starts
  almost where it was.
* ``large``: AFN large, the paper's high-spp architecture (three scales of 5x5 kernels, no TA
  input), a different graph in model_large.py; :func:`make_model` builds either.

Cost (default widths, from :func:`cost_per_pixel`; FLOP = 2 per multiply-add, per full-res pixel):
kernel prediction 15016 FLOP (13.8 GFLOP at 1280x720), filtering + fusion ~563 FLOP,
refinement 8352 FLOP (7.7 GFLOP); 70,432 parameters in total (tests/test_afn_model.py).
"""

from dataclasses import dataclass, field

import torch
import torch.nn.functional as F
from torch import nn

from .color import ALBEDO_EPS, tonemap
from .shifted_filter import shifted_filter

KERNEL_SIZE = 7
KERNEL_TAPS = KERNEL_SIZE * KERNEL_SIZE
INPUT_CHANNELS = 13            # T(1spp) 3, T(TA) 3, albedo 3, normal01 3, depth01 1 (+ history01)
REFINE_INPUT_CHANNELS = 10     # T(i) 3, albedo 3, normal01 3, depth01 1
PAD_MULTIPLE = 8               # three 2x pooling levels
QUARTER_CENTRE_LOGIT = 6.0     # the quarter scale's initial centre-tap logit (docstring)
ALBEDO_TRUST_BIAS = -6.0       # headG's initial bias: colour-space share t = 0.0025 (docstring)
VARIANTS = ("full", "fusion", "1spp", "ta", "large")


@dataclass
class AFNConfig:
    """Architecture of one AFN model (stored in the weights archive's metadata)."""

    variant: str = "full"                               # one of VARIANTS
    enc: tuple = field(default_factory=lambda: (16, 32, 64))  # e1, e2, e3 widths
    dec: tuple = field(default_factory=lambda: (32, 24))      # d2, d1 widths
    refine: int = 16                                    # refinement hidden width
    inputs: str = "albedo,normal,depth,temporal"        # input set trained for (input_sets.py)
    spp: int = 1        # samples per pixel of the training inputs: the C++ core picks by it
    quarter: bool = False   # the quarter-resolution scale (module docstring)
    history: bool = False   # the history01 input channel (module docstring)
    albedo_trust: bool = False  # the learned albedo trust, headG (module docstring)

    def to_dict(self):
        return {"variant": self.variant, "enc": list(self.enc), "dec": list(self.dec),
                "refine": self.refine, "inputs": self.inputs, "spp": self.spp,
                "quarter": self.quarter, "history": self.history,
                "albedo_trust": self.albedo_trust}

    @staticmethod
    def from_dict(d):
        return AFNConfig(variant=d.get("variant", "full"), enc=tuple(d.get("enc", (16, 32, 64))),
                         dec=tuple(d.get("dec", (32, 24))), refine=int(d.get("refine", 16)),
                         inputs=d.get("inputs", "albedo,normal,depth,temporal"),
                         spp=int(d.get("spp", 1)), quarter=bool(d.get("quarter", False)),
                         history=bool(d.get("history", False)),
                         albedo_trust=bool(d.get("albedo_trust", False)))


def input_channels(cfg: AFNConfig) -> int:
    """Channels of the network input x: 13, or 14 with the history input."""
    return INPUT_CHANNELS + (1 if cfg.history else 0)


def down2(x: torch.Tensor) -> torch.Tensor:
    """D: 2x2 average pooling (B, C, H, W) -> (B, C, H/2, W/2); H, W even."""
    return F.avg_pool2d(x, 2)


def up2(x: torch.Tensor) -> torch.Tensor:
    """U: nearest-neighbour 2x upsampling (B, C, H, W) -> (B, C, 2H, 2W)."""
    return F.interpolate(x, scale_factor=2, mode="nearest")


def apply_kernels(img: torch.Tensor, kernels: torch.Tensor) -> torch.Tensor:
    """Per-pixel 7x7 filtering (Eq. 2) by shifted slices (never unfolds the image).

    Args:
        img: (B, C, H, W) linear HDR.
        kernels: (B, 49, H, W) normalised weights; tap j = (dy+3)*7 + (dx+3) reads img[y+dy, x+dx].

    Returns:
        (B, C, H, W): ``sum_j K_j * img(p + offset_j)``, zero outside the image.
    """
    r = KERNEL_SIZE // 2
    return shifted_filter(F.pad(img, (r, r, r, r)), kernels, KERNEL_SIZE)


def up4_bilinear(x: torch.Tensor) -> torch.Tensor:
    """U4: bilinear 4x upsampling, align_corners=False (sample (x + 0.5) / 4 - 0.5, clamped)."""
    return F.interpolate(x, scale_factor=4, mode="bilinear", align_corners=False)


def fuse_quarter(i: torch.Tensor, k_q: torch.Tensor, beta: torch.Tensor) -> torch.Tensor:
    """The quarter-resolution scale: ``i + U4(beta * (K_q * l - l))`` with ``l = D(D(i))``.

    Args:
        i: (B, 3, H, W) fused image, H and W multiples of 4.
        k_q: (B, 49, H/4, W/4) normalised kernels; beta: (B, 1, H/4, W/4) in [0, 1].
    """
    low = down2(down2(i))
    return i + up4_bilinear(beta * (apply_kernels(low, k_q) - low))


def fuse(d_ta: torch.Tensor, d_1spp_half: torch.Tensor, alpha: torch.Tensor) -> torch.Tensor:
    """Eq. 3: ``i = d_TA - alpha * U(D(d_TA)) + alpha * U(d_1spp)``.

    Args:
        d_ta: (B, 3, H, W) filtered TA frame, H and W even.
        d_1spp_half: (B, 3, H/2, W/2) filtered down-sampled 1-spp frame.
        alpha: (B, 1, H, W) fusion weights in [0, 1].
    """
    return d_ta - alpha * up2(down2(d_ta)) + alpha * up2(d_1spp_half)


def albedo_trust_scale(albedo: torch.Tensor, t_half: torch.Tensor) -> torch.Tensor:
    """The learned albedo trust's rescaling ``s = max(a, eps) / max(a', eps)``,
    ``a' = a + (1 - a) * U(t)`` (module docstring).

    Args:
        albedo: (B, 3, H, W) the demodulation albedo a, in [0, 1].
        t_half: (B, 1, H/2, W/2) colour-space share t in [0, 1].
    """
    t = up2(t_half)
    blended = albedo + (1.0 - albedo) * t
    return torch.clamp(albedo, min=ALBEDO_EPS) / torch.clamp(blended, min=ALBEDO_EPS)


def pad_to_multiple(x: torch.Tensor, m: int = PAD_MULTIPLE) -> torch.Tensor:
    """Replicate-pad (B, C, H, W) at the right and bottom to multiples of m."""
    h, w = x.shape[-2:]
    ph, pw = (-h) % m, (-w) % m
    if ph == 0 and pw == 0:
        return x
    return F.pad(x, (0, pw, 0, ph), mode="replicate")


def conv3(cin, cout):
    """A 3x3 convolution keeping the size (zero padding 1)."""
    return nn.Conv2d(cin, cout, 3, padding=1)


def add_unet(net: nn.Module, in_channels: int, cfg: AFNConfig) -> None:
    """Give ``net`` the half-res-start U-Net M of AFN and AFN large: ``enc1``..``enc3``, ``dec2``,
    ``dec1`` (3x3 convs, widths ``cfg.enc`` and ``cfg.dec``), registered in that order (which
    fixes the parameters' initialisation and the archive's tensor order)."""
    c1, c2, c3 = cfg.enc
    d2, d1 = cfg.dec
    net.enc1 = conv3(in_channels, c1)
    net.enc2 = conv3(c1, c2)
    net.enc3 = conv3(c2, c3)
    net.dec2 = conv3(c3 + c2, d2)
    net.dec1 = conv3(d2 + c1, d1)


def run_unet(net: nn.Module, x: torch.Tensor, with_e1: bool = False):
    """M of :func:`add_unet` on x (B, C, H, W), H and W multiples of 8: the decoder features
    ``d2`` (1/4 res) and ``d1`` (1/2 res), ReLU applied (and the first encoder level ``e1``,
    1/2 res, with ``with_e1``)."""
    e1 = F.relu(net.enc1(down2(x)))                               # 1/2
    e2 = F.relu(net.enc2(down2(e1)))                              # 1/4
    e3 = F.relu(net.enc3(down2(e2)))                              # 1/8
    d2 = F.relu(net.dec2(torch.cat([up2(e3), e2], 1)))            # 1/4
    d1 = F.relu(net.dec1(torch.cat([up2(d2), e1], 1)))            # 1/2
    return (d2, d1, e1) if with_e1 else (d2, d1)


def conv_flop(cin, cout, k, scale):
    """FLOP per full-res pixel (2 per multiply-add) of a k x k convolution on 1/scale of them."""
    return 2 * k * k * cin * cout / scale


def unet_flop(in_channels: int, cfg: AFNConfig) -> float:
    """FLOP per full-res pixel of the U-Net of :func:`add_unet` (at 1/2, 1/4 and 1/8 res)."""
    c1, c2, c3 = cfg.enc
    d2, d1 = cfg.dec
    return (conv_flop(in_channels, c1, 3, 4) + conv_flop(c1, c2, 3, 16)
            + conv_flop(c2, c3, 3, 64) + conv_flop(c3 + c2, d2, 3, 16)
            + conv_flop(d2 + c1, d1, 3, 4))


class AFN(nn.Module):
    """AFN: multi-scale kernel prediction, filtering + fusion, refinement (module docstring).

    Example:
        >>> net = AFN(AFNConfig())
        >>> out = net(c1, cta, albedo, normal01, depth01)   # each (B, C, H, W)
        >>> out["o"].shape   # (B, 3, H, W), demodulated; remodulate with color.remodulate
    """

    def __init__(self, cfg: AFNConfig = None):
        super().__init__()
        cfg = cfg or AFNConfig()
        if cfg.variant not in VARIANTS or cfg.variant == "large":
            raise ValueError(f"unknown AFN variant '{cfg.variant}' (known: "
                             f"{', '.join(VARIANTS[:-1])}; 'large' is built by make_model)")
        self.cfg = cfg
        d2, d1 = cfg.dec
        if cfg.history and cfg.variant not in ("full", "fusion"):
            raise ValueError(f"the history input needs variant full or fusion, not "
                             f"'{cfg.variant}'")
        cin = input_channels(cfg)
        add_unet(self, cin, cfg)
        self.head1 = nn.Conv2d(d1, KERNEL_TAPS, 1)
        self.headTA = nn.Conv2d(d1 + cin, KERNEL_TAPS + 1, 1)
        if cfg.quarter and cfg.variant not in ("full", "fusion"):
            raise ValueError(f"the quarter-resolution scale needs variant full or fusion, not "
                             f"'{cfg.variant}'")
        if cfg.quarter:
            self.head4 = nn.Conv2d(d2, KERNEL_TAPS + 1, 1)
            with torch.no_grad():               # near-identity kernels, beta 0.5 (docstring)
                self.head4.weight.zero_()
                self.head4.bias.zero_()
                self.head4.bias[KERNEL_TAPS // 2] = QUARTER_CENTRE_LOGIT
        if cfg.albedo_trust and cfg.variant not in ("full", "fusion"):
            raise ValueError(f"the albedo trust needs variant full or fusion, not "
                             f"'{cfg.variant}'")
        if cfg.albedo_trust:
            self.headG = conv3(cfg.enc[0], 1)
            with torch.no_grad():               # almost the paper's demodulation (docstring)
                self.headG.weight.zero_()
                self.headG.bias.fill_(ALBEDO_TRUST_BIAS)
        self.use_refine = cfg.variant == "full"
        if self.use_refine:
            self.ref1 = conv3(REFINE_INPUT_CHANNELS, cfg.refine)
            self.ref2 = conv3(cfg.refine, cfg.refine)
            self.ref3 = conv3(cfg.refine, 3)

    def forward(self, c1, cta, albedo, normal01, depth01, history01=None):
        """Denoise one batch.

        Args:
            c1: (B, 3, H, W) 1-spp colour, albedo-demodulated, linear HDR, non-negative.
            cta: (B, 3, H, W) TA-1spp colour, demodulated, linear HDR.
            albedo: (B, 3, H, W) in [0, 1].
            normal01: (B, 3, H, W) shading normal scaled to [0, 1].
            depth01: (B, 1, H, W) depth scaled to [0, 1] per frame.
            history01: (B, 1, H, W) 1 / frames in the TA input, in [1/255, 1]; required by a
                model with ``cfg.history``, ignored by others.

        Returns:
            dict with ``o`` (B, 3, H, W) demodulated output and the intermediates (padded size):
                ``i`` fused image, ``d_ta``, ``d_1spp`` (half res), ``alpha``, ``k_ta``, ``k_1spp``
            (and ``t``, half res, with the albedo trust; ``i`` is then in the a'-demodulated
            space).
        """
        h, w = c1.shape[-2:]
        if self.cfg.variant == "1spp":
            cta = c1
        elif self.cfg.variant == "ta":
            c1 = cta
        c1, cta, albedo, normal01, depth01 = (
            pad_to_multiple(t) for t in (c1, cta, albedo, normal01, depth01))
        feats = torch.cat([albedo, normal01, depth01], 1)
        x = torch.cat([tonemap(c1), tonemap(cta), feats], 1)          # (B, 13, H, W)
        if self.cfg.history:
            if history01 is None:
                raise ValueError("this model takes the history input: pass history01")
            x = torch.cat([x, pad_to_multiple(history01)], 1)         # (B, 14, H, W)
        d2, d1, e1 = run_unet(self, x, with_e1=True)                  # 1/4, 1/2, 1/2
        extra = {}
        if self.cfg.albedo_trust:                                     # module docstring
            extra["t"] = torch.sigmoid(self.headG(e1))                # (B, 1, H/2, W/2)
            scale = albedo_trust_scale(albedo, extra["t"])
            c1, cta = c1 * scale, cta * scale
        k_1spp = torch.softmax(self.head1(d1), 1)                     # (B, 49, H/2, W/2)
        full = self.headTA(torch.cat([up2(d1), x], 1))                # (B, 50, H, W)
        k_ta = torch.softmax(full[:, :KERNEL_TAPS], 1)                # (B, 49, H, W)
        alpha = torch.sigmoid(full[:, KERNEL_TAPS:])                  # (B, 1, H, W)
        d_ta = apply_kernels(cta, k_ta)
        d_1spp = apply_kernels(down2(c1), k_1spp)
        i = fuse(d_ta, d_1spp, alpha)
        if self.cfg.quarter:
            q = self.head4(d2)                                        # (B, 50, H/4, W/4)
            extra.update(k_q=torch.softmax(q[:, :KERNEL_TAPS], 1),
                         beta=torch.sigmoid(q[:, KERNEL_TAPS:]))
            i = fuse_quarter(i, extra["k_q"], extra["beta"])
        o = i
        if self.use_refine:
            r = torch.cat([tonemap(i), feats], 1)
            r = F.relu(self.ref1(r))
            r = F.relu(self.ref2(r))
            o = i + self.ref3(r)
        if self.cfg.albedo_trust:
            o = o / scale                       # back to the albedo-demodulated space
        return {"o": o[..., :h, :w], "i": i, "d_ta": d_ta, "d_1spp": d_1spp, "alpha": alpha,
                "k_ta": k_ta, "k_1spp": k_1spp, **extra}


def make_model(cfg: AFNConfig = None) -> nn.Module:
    """The network of ``cfg``: :class:`AFN`, or ``AFNLarge`` (model_large.py) for "large"."""
    cfg = cfg or AFNConfig()
    if cfg.variant == "large":
        from .model_large import AFNLarge
        return AFNLarge(cfg)
    return AFN(cfg)


def cost_per_pixel(cfg: AFNConfig = None) -> dict:
    """FLOP per full-resolution pixel of each stage (2 FLOP per multiply-add) and parameter count.

    Filtering counts 2 FLOP per tap and channel plus ~3 per softmax tap (exp, sum, divide).
    """
    cfg = cfg or AFNConfig()
    if cfg.variant == "large":
        from . import model_large
        return model_large.cost_per_pixel(cfg)
    d2, d1 = cfg.dec
    cin = input_channels(cfg)
    kp = (unet_flop(cin, cfg) + conv_flop(d1, KERNEL_TAPS, 1, 4)
          + conv_flop(d1 + cin, KERNEL_TAPS + 1, 1, 1))
    filt = (KERNEL_TAPS * (2 * 3 + 3)) * (1 + 0.25) + 12
    if cfg.albedo_trust:    # headG at 1/2 and the rescaling of two colours
        kp += conv_flop(cfg.enc[0], 1, 3, 4) + 12
    if cfg.quarter:     # head4 and one 7x7 filter at 1/4, pooling and the bilinear upsampling
        kp += conv_flop(d2, KERNEL_TAPS + 1, 1, 16)
        filt += KERNEL_TAPS * (2 * 3 + 3) / 16 + 3 * 8
    ref = 0.0
    if cfg.variant == "full":
        ref = (conv_flop(REFINE_INPUT_CHANNELS, cfg.refine, 3, 1)
               + conv_flop(cfg.refine, cfg.refine, 3, 1) + conv_flop(cfg.refine, 3, 3, 1))
    params = sum(p.numel() for p in AFN(cfg).parameters())
    return {"kernel_prediction": kp, "filtering_fusion": filt, "refinement": ref,
            "total": kp + filt + ref, "parameters": params}
