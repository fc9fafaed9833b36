# SPDX-License-Identifier: Apache-2.0
"""Write the PyTorch <-> C++ parity vectors of the baselines to tests/data/baselines_parity/.

    /usr/bin/python3 -m afn.baselines.make_parity_vectors            (from training/)

Files (weights-archive format, :mod:`afn.weights`):
  wskpn_weights.afnw  a deterministic random WSKPN, folded as the export folds it (the C++ engine
                      runs the folded 5x5 layers); head logits scaled x3 so weights and fusion are
                      far from uniform
  wskpn_case.afnw     inputs cta, albedo, normal01, depth01 (H, W, C) and the outputs of the folded
                      PyTorch model: head (12 ch), o; plus o_branches, the unfolded training model's
                      output (the folding check)
  nbgd_weights.afnw   a deterministic random NBGD (guide2 scaled x4: guides spread over [0, 255])
  nbgd_case.afnw      the same inputs and guides (5 ch sigmoid), g1, g2, g3 (sliced grids), o
The frame is 37x21 (odd; the 16-pixel grid has 4 x 3 cells).
"""

import argparse
import os

import numpy as np
import torch

from ..make_parity_vectors import HEIGHT, WIDTH, make_inputs
from ..weights import dumps
from . import archive, nbgd, wskpn

KEYS = ("cta", "albedo", "normal01", "depth01")


def _t(a):
    return torch.from_numpy(a).permute(2, 0, 1)[None]


def _np(t):
    return t[0].permute(1, 2, 0).contiguous().numpy()


def make_wskpn(seed=0):
    torch.manual_seed(seed)
    model = wskpn.WSKPN().eval()
    with torch.no_grad():
        for branch in ("b5", "b3", "b1"):
            getattr(model.blocks[-1], branch).weight.mul_(3.0)
    return model


def make_nbgd(seed=0):
    torch.manual_seed(seed)
    model = nbgd.NBGD().eval()
    with torch.no_grad():
        model.guide2.weight.mul_(4.0)
    return model


def cases(inputs):
    """{method: (weights bytes, case tensors)}."""
    args = [_t(inputs[k]) for k in KEYS]
    out = {}
    model = make_wskpn()
    weights = archive.archive_bytes("wskpn", model)
    folded = wskpn.FoldedWSKPN(model.folded_state()).eval()
    with torch.no_grad():
        f = folded(*args)
        b = model(*args)
    out["wskpn"] = (weights, {"head": _np(f["head"]), "o": _np(f["o"]),
                              "o_branches": _np(b["o"])})
    model = make_nbgd()
    with torch.no_grad():
        r = model(*args)
    out["nbgd"] = (archive.archive_bytes("nbgd", model),
                   {k: _np(r[k]) for k in ("guides", "g1", "g2", "g3", "o")})
    return out


def main(argv=None):
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.join(here, "..", "..", "..", "tests", "data", "baselines_parity")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=default_out)
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    full = make_inputs()
    inputs = {k: full[k] for k in KEYS}
    for method, (weights, outputs) in cases(inputs).items():
        with open(os.path.join(args.out, f"{method}_weights.afnw"), "wb") as f:
            f.write(weights)
        with open(os.path.join(args.out, f"{method}_case.afnw"), "wb") as f:
            f.write(dumps({**inputs, **outputs}, {"width": WIDTH, "height": HEIGHT,
                                                  "method": method, "torch": torch.__version__}))
        o = outputs["o"]
        print(f"{method}: o range [{o.min():.4f}, {o.max():.4f}]")
    print(f"wrote {os.path.normpath(args.out)}")


if __name__ == "__main__":
    main()
