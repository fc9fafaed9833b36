# SPDX-License-Identifier: Apache-2.0
"""AFN large: the paper's architecture for high sample counts (Lee et al., Appendix VII-A and the
Tungsten experiments of Section V), variant ``large`` of :class:`afn.model.AFNConfig`.

The paper's words: "since TA images are not used here, we perform filtering and fusion by
down-sampling 64 spp to three scales"; "The proposed denoiser (large) predict 3 scales of 5x5
kernel maps, i.e., K1, K2, K3. Next, each kernel is applied to the original and down-scaled 64spp
images, and filtered images are fused progressively. Finally, large refinement modules are
applied to remove residual noise and improve fine details." Its Figure 7 is not in the text, so
the rest is chosen here (the C++ engine, lib/core/methods/afn/network_large.cpp, implements
exactly this graph; same tensor names):

* No TA input: the network reads the current (high-spp) colour c only; the ``cta`` argument of
  ``forward`` is accepted and ignored, so the training loop and the C++ input preparation stay
  those of AFN. Network input x (10 ch, full res): T(c), albedo, normal01, depth01
  (T as model.py).
* Encoder-decoder M: AFN's half-res-start U-Net (model.py) on x, 3x3 convs, ReLU, the same
  default widths: ``e1 = enc1(D x)`` 10->16 (1/2), ``e2 = enc2(D e1)`` 16->32 (1/4),
  ``e3 = enc3(D e2)`` 32->64 (1/8), ``d2 = dec2([U e3, e2])`` 96->32 (1/4),
  ``d1 = dec1([U d2, e1])`` 48->24 (1/2).
* Three scales of 5x5 kernels (1x1 heads): ``K3 = head3(d2)`` 32->25 at 1/4, applied to D(D(c));
  ``[K2, a2] = head2(d1)`` 24->26 at 1/2, applied to D(c); ``[K1, a1] = head1([U d1, x])`` 34->26
  at full res, applied to c (AFN's trick for per-pixel full-res kernels without a full-res 3x3
  conv). Kernels: softmax over the 25 taps, tap j = (dy+2)*5 + (dx+2); the image is read with
  edge replication outside the frame (as MR-KP; unlike AFN's zero padding, a constant image then
  stays exactly constant through filtering and fusion, borders included).
* Progressive fusion, coarse to fine: AFN's Eq. 3 applied scale by scale, with a_s =
  sigmoid(logit) per pixel of the finer scale (which is also MR-KP's scale composition)::

      o3 = f3
      o2 = f2 - a2 * U(D(f2)) + a2 * U(o3)        (1/2)
      i  = f1 - a1 * U(D(f1)) + a1 * U(o2)        (full res)

  i.e. each scale keeps its own high frequencies and takes its low frequencies, by a learned
  per-pixel amount, from the coarser (less noisy) fused scale.
* "Large refinement modules": two of AFN's refinement modules in sequence, each
  ``o <- o + R_m([T(o), albedo, normal01, depth01])`` with R_m = 3x3 convs 10->w->w->3 and ReLU
  between (w = ``refine``, default 16); names ``refA1..3``, ``refB1..3``.
* Padding to a multiple of 8 (three pooling levels) by edge replication, output cropped: as AFN.

Cost at the default widths (:func:`cost_per_pixel`, FLOP per full-res pixel): kernel prediction
12.7 kFLOP, filtering + fusion about 0.3 kFLOP, refinement 16.7 kFLOP (29.7 k in all, AFN's
23.9 k); 73,471 parameters (about 295 KB as .afnw).
"""

import torch
import torch.nn.functional as F
from torch import nn

from .color import tonemap
from .model import (add_unet, conv3, conv_flop, down2, pad_to_multiple, run_unet, unet_flop,
                    up2)
from .shifted_filter import shifted_filter

LARGE_KERNEL_SIZE = 5
LARGE_TAPS = LARGE_KERNEL_SIZE * LARGE_KERNEL_SIZE
LARGE_INPUT_CHANNELS = 10       # T(c) 3, albedo 3, normal01 3, depth01 1
REFINE_INPUT_CHANNELS = 10      # T(o) 3, albedo 3, normal01 3, depth01 1
REFINE_MODULES = ("refA", "refB")


def apply_kernels5(img, kernels):
    """Per-pixel 5x5 filtering with edge replication outside the image.

    Args:
        img: (B, C, H, W) linear HDR.
        kernels: (B, 25, H, W) normalised weights; tap j = (dy+2)*5 + (dx+2) reads
            img[clamp(y+dy), clamp(x+dx)].

    Returns:
        (B, C, H, W).
    """
    r = LARGE_KERNEL_SIZE // 2
    return shifted_filter(F.pad(img, (r, r, r, r), mode="replicate"), kernels, LARGE_KERNEL_SIZE)


def fuse_scale(fine, coarse, alpha):
    """Eq. 3 between two scales: ``fine - alpha * U(D(fine)) + alpha * U(coarse)``."""
    return fine - alpha * up2(down2(fine)) + alpha * up2(coarse)


class AFNLarge(nn.Module):
    """AFN large (module docstring); built by :func:`afn.model.make_model` for variant "large"."""

    def __init__(self, cfg):
        super().__init__()
        if cfg.variant != "large":
            raise ValueError(f"AFNLarge needs variant 'large', not '{cfg.variant}'")
        self.cfg = cfg
        d2, d1 = cfg.dec
        add_unet(self, LARGE_INPUT_CHANNELS, cfg)
        self.head3 = nn.Conv2d(d2, LARGE_TAPS, 1)
        self.head2 = nn.Conv2d(d1, LARGE_TAPS + 1, 1)
        self.head1 = nn.Conv2d(d1 + LARGE_INPUT_CHANNELS, LARGE_TAPS + 1, 1)
        for m in REFINE_MODULES:
            setattr(self, f"{m}1", conv3(REFINE_INPUT_CHANNELS, cfg.refine))
            setattr(self, f"{m}2", conv3(cfg.refine, cfg.refine))
            setattr(self, f"{m}3", conv3(cfg.refine, 3))

    def forward(self, c1, cta, albedo, normal01, depth01):
        """Denoise one batch (arguments as :meth:`afn.model.AFN.forward`; ``cta`` is unused).

        Returns:
            dict with ``o`` (B, 3, H, W) demodulated output and, at the padded size: ``i`` the
            fused image, ``f1``/``f2``/``f3`` the filtered scales (full, 1/2, 1/4), ``o2`` the
            fused half scale, ``alpha1``/``alpha2`` the fusion weights, ``k1``/``k2``/``k3``.
        """
        del cta   # no TA input (module docstring)
        h, w = c1.shape[-2:]
        c, albedo, normal01, depth01 = (pad_to_multiple(t) for t in (c1, albedo, normal01, depth01))
        feats = torch.cat([albedo, normal01, depth01], 1)
        x = torch.cat([tonemap(c), feats], 1)                        # (B, 10, H, W)
        d2, d1 = run_unet(self, x)                                    # 1/4, 1/2
        k3 = torch.softmax(self.head3(d2), 1)
        h2 = self.head2(d1)
        k2, alpha2 = torch.softmax(h2[:, :LARGE_TAPS], 1), torch.sigmoid(h2[:, LARGE_TAPS:])
        h1 = self.head1(torch.cat([up2(d1), x], 1))
        k1, alpha1 = torch.softmax(h1[:, :LARGE_TAPS], 1), torch.sigmoid(h1[:, LARGE_TAPS:])
        c_half = down2(c)
        f3 = apply_kernels5(down2(c_half), k3)
        f2 = apply_kernels5(c_half, k2)
        f1 = apply_kernels5(c, k1)
        o2 = fuse_scale(f2, f3, alpha2)
        i = fuse_scale(f1, o2, alpha1)
        o = i
        for m in REFINE_MODULES:
            r = F.relu(getattr(self, f"{m}1")(torch.cat([tonemap(o), feats], 1)))
            r = F.relu(getattr(self, f"{m}2")(r))
            o = o + getattr(self, f"{m}3")(r)
        return {"o": o[..., :h, :w], "i": i, "f1": f1, "f2": f2, "f3": f3, "o2": o2,
                "alpha1": alpha1, "alpha2": alpha2, "k1": k1, "k2": k2, "k3": k3}


def cost_per_pixel(cfg):
    """FLOP per full-res pixel of each stage (2 per multiply-add) and the parameter count."""
    d2, d1 = cfg.dec
    kp = (unet_flop(LARGE_INPUT_CHANNELS, cfg) + conv_flop(d2, LARGE_TAPS, 1, 16)
          + conv_flop(d1, LARGE_TAPS + 1, 1, 4)
          + conv_flop(d1 + LARGE_INPUT_CHANNELS, LARGE_TAPS + 1, 1, 1))
    filt = LARGE_TAPS * (2 * 3 + 3) * (1 + 1 / 4 + 1 / 16) + 2 * 12
    ref = len(REFINE_MODULES) * (conv_flop(REFINE_INPUT_CHANNELS, cfg.refine, 3, 1)
                                 + conv_flop(cfg.refine, cfg.refine, 3, 1)
                                 + conv_flop(cfg.refine, 3, 3, 1))
    params = sum(p.numel() for p in AFNLarge(cfg).parameters())
    return {"kernel_prediction": kp, "filtering_fusion": filt, "refinement": ref,
            "total": kp + filt + ref, "parameters": params}
