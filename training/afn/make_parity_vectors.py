# SPDX-License-Identifier: Apache-2.0
"""Write the PyTorch <-> C++ parity vectors to tests/data/afn_parity/ (one command).

    /usr/bin/python3 -m afn.make_parity_vectors            (from training/)

Files (all in the weights-archive format of weights.py, so the C++ reader is exercised too):
  weights_<variant>.afnw   deterministic random-initialised small model (narrow widths, so the
                           C++ engine must derive every width from the tensor dims)
  case_<variant>.afnw      inputs c1, cta, albedo, normal01, depth01 and the PyTorch outputs
                           o (cropped), i, d_ta, d_1spp, alpha (padded size); images are stored
                           (H, W, C) interleaved, float32.
  weights_quarter.afnw, case_quarter.afnw   variant full with the quarter-resolution scale
                           (model.py ``quarter``): head4 scaled like the heads and its beta
                           bias set to 0, so the scale contributes half its delta.
  weights_history.afnw, case_history.afnw   variant full with the history input (model.py
                           ``history``; the case holds history01 too), its weights random.
  weights_trust.afnw, case_trust.afnw   variant full with the history input and the learned
                           albedo trust (model.py ``albedo_trust``): headG random (bias 0, so t
                           spreads over (0, 1)); the case holds t (half res) too.
  weights_large.afnw, case_large.afnw   the same for AFN large (model_large.py): outputs o, i,
                           f1, alpha1 (full res), o2 (1/2), f3 (1/4), padded size.
(tests/data/afn_parity/ta_case.afnw, a golden case of the core's temporal accumulation, was made
by an earlier numpy TA; the toolkit now prepares its inputs through afntool and has no TA of its
own, so that file is kept as committed.)
The frame is 37x21 (odd, not a multiple of 8) so the pad-to-8 rule is covered.
"""

import argparse
import os

import numpy as np
import torch

from .model import AFNConfig
from .model import make_model as build_model
from .weights import dumps, save_model

WIDTH, HEIGHT = 37, 21
PARITY_CONFIG = dict(enc=(8, 12, 16), dec=(12, 8), refine=8)


def make_inputs(seed: int = 1):
    """Deterministic HDR-ish inputs (numpy, (H, W, C) float32)."""
    rng = np.random.RandomState(seed)
    h, w = HEIGHT, WIDTH
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    base = 0.5 + 0.4 * np.sin(xx[..., None] * 0.3 + np.arange(3) * 1.3) * np.cos(yy[..., None] * 0.2)
    c1 = (base * rng.exponential(1.0, (h, w, 3)) * 1.5).astype(np.float32)   # values up to ~10
    cta = (base + 0.1 * rng.standard_normal((h, w, 3))).clip(0).astype(np.float32)
    albedo = rng.uniform(0.05, 1.0, (h, w, 3)).astype(np.float32)
    n = rng.standard_normal((h, w, 3))
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    normal01 = (n * 0.5 + 0.5).astype(np.float32)
    depth01 = ((xx + yy) / (w + h - 2))[..., None].astype(np.float32)
    history01 = (1.0 / rng.randint(1, 10, (h, w, 1))).astype(np.float32)
    return {"c1": c1, "cta": cta, "albedo": albedo, "normal01": normal01, "depth01": depth01,
            "history01": history01}


OUTPUTS = {"large": ("o", "i", "f1", "alpha1", "o2", "f3"),
           "trust": ("o", "i", "d_ta", "d_1spp", "alpha", "t")}
DEFAULT_OUTPUTS = ("o", "i", "d_ta", "d_1spp", "alpha")


def make_model(variant: str, seed: int = 0):
    """Random-initialised model; heads scaled x4 so the kernels are far from uniform.
    ``quarter`` is variant full with the quarter scale."""
    torch.manual_seed(seed)
    quarter, trust = variant == "quarter", variant == "trust"
    history = variant in ("history", "trust")
    cfg = AFNConfig(variant="full" if quarter or history else variant, quarter=quarter,
                    history=history, albedo_trust=trust, **PARITY_CONFIG)
    model = build_model(cfg).eval()
    heads = ("head1", "head2", "head3") if variant == "large" else ("head1", "headTA")
    with torch.no_grad():
        for name in heads:
            getattr(model, name).weight.mul_(4.0)
        if quarter:
            model.head4.weight.normal_(0.0, 0.5)
            model.head4.bias.zero_()
        if trust:
            model.headG.weight.normal_(0.0, 0.5)
            model.headG.bias.zero_()
    return model



def run(model, inputs: dict) -> dict:
    """PyTorch forward on (H, W, C) numpy inputs; returns (H, W, C) numpy outputs."""
    def t(a):
        return torch.from_numpy(a).permute(2, 0, 1)[None]
    with torch.no_grad():
        keys = ("c1", "cta", "albedo", "normal01", "depth01")
        keys += ("history01",) if getattr(model.cfg, "history", False) else ()
        out = model(*(t(inputs[k]) for k in keys))
    names = OUTPUTS["trust"] if getattr(model.cfg, "albedo_trust", False) else OUTPUTS.get(
        model.cfg.variant, DEFAULT_OUTPUTS)
    return {k: out[k][0].permute(1, 2, 0).contiguous().numpy() for k in names}


def main(argv=None):
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.join(here, "..", "..", "tests", "data", "afn_parity")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=default_out, help="output folder (default: %(default)s)")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    inputs = make_inputs()
    for variant in ("full", "fusion", "large", "quarter", "history", "trust"):
        model = make_model(variant)
        save_model(os.path.join(args.out, f"weights_{variant}.afnw"), model)
        outputs = run(model, inputs)
        # history01 only in the case of the model that reads it (the others stay as committed).
        reads_history = variant in ("history", "trust")
        case_inputs = {k: v for k, v in inputs.items() if k != "history01" or reads_history}
        with open(os.path.join(args.out, f"case_{variant}.afnw"), "wb") as f:
            f.write(dumps({**case_inputs, **outputs},
                          {"width": WIDTH, "height": HEIGHT, "variant": variant,
                           "torch": torch.__version__}))
        print(f"{variant}: o range [{outputs['o'].min():.4f}, {outputs['o'].max():.4f}]")
    print(f"wrote {os.path.normpath(args.out)}")


if __name__ == "__main__":
    main()
