# SPDX-License-Identifier: Apache-2.0
"""Write the PyTorch <-> C++ parity vectors of ONND and MR-KP to
tests/data/baselines_parity/ (one command):

    /usr/bin/python3 -m afn.baselines.onnd_mrkp_parity_vectors       (from training/)

Files (weights-archive format, weights.py):
  <name>_weights.afnw   deterministic random-initialised model (narrow widths for ONND, so the
                        C++ engine must derive every width from the tensor dims)
  <name>_case.afnw      per frame t: inputs cta<t>, albedo<t>, normal01<t>, depth01<t> and the
                        PyTorch output irr<t> (demodulated irradiance), (H, W, C) float32.
ONND runs three frames (the recurrent state carried from frame to frame) whose colour has flat,
black and low-contrast patches (the contrast gate's regimes); MR-KP one. The frame is
37x21 (odd, not a multiple of 16) so the padding rule is covered.
"""

import argparse
import os

import numpy as np
import torch

from ..make_parity_vectors import HEIGHT, WIDTH, make_inputs
from . import mrkp, onnd
from .onnd_mrkp_train import export
from ..weights import dumps

ONND_PARITY = dict(enc=(6, 8, 10), bottleneck=12)
MRKP_PARITY = dict(width=12)


def frames(count, gate_patches=False):
    """Inputs of `count` frames (numpy (H, W, C)), different per frame. With `gate_patches`
    (ONND) the colour has a flat patch, a black patch (gate exactly 0: output = input) and a
    low-contrast patch (gate between 0 and 1), so the contrast gate's three regimes are compared."""
    out = []
    for t in range(count):
        i = make_inputs(seed=1 + t)
        cta = i["cta"] * (1.0 + 2.0 * t)
        if gate_patches:
            rng = np.random.RandomState(100 + t)
            cta[2:9, 3:12] = np.float32([0.8, 0.6, 0.4]) * (1.0 + t)
            cta[12:19, 22:33] = 0.0
            cta[2:9, 20:31] = 0.5 + 0.01 * rng.standard_normal((7, 11, 3)).astype(np.float32)
        out.append({"cta": cta, "albedo": i["albedo"],
                    "normal01": i["normal01"], "depth01": i["depth01"]})
    return out


def tensor(a):
    return torch.from_numpy(a).permute(2, 0, 1)[None]


def main(argv=None):
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.join(here, "..", "..", "..", "tests", "data", "baselines_parity")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=default_out, help="output folder (default: %(default)s)")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    torch.manual_seed(0)
    models = {"onnd": onnd.ONND(**ONND_PARITY).eval(), "mrkp": mrkp.MRKP(**MRKP_PARITY).eval()}
    with torch.no_grad():   # kernels far from uniform, blend weights away from 0.5
        for l in range(mrkp.FILTER_LEVELS):
            getattr(models["mrkp"], f"head{l}").weight.mul_(4.0)
    for name, model in models.items():
        export(os.path.join(args.out, f"{name}_weights.afnw"), model, name)
        seq = frames(3, gate_patches=True) if name == "onnd" else frames(1)
        case, state = {}, None
        with torch.no_grad():
            for t, f in enumerate(seq):
                x = [tensor(f[k]) for k in ("cta", "albedo", "normal01", "depth01")]
                if name == "onnd":
                    irr, state = model(*x, state)
                else:
                    irr = model(*x)
                case.update({f"{k}{t}": v for k, v in f.items()})
                case[f"irr{t}"] = irr[0].permute(1, 2, 0).contiguous().numpy()
        with open(os.path.join(args.out, f"{name}_case.afnw"), "wb") as fh:
            fh.write(dumps(case, {"width": WIDTH, "height": HEIGHT, "frames": len(seq),
                                  "torch": torch.__version__}))
        last = case[f"irr{len(seq) - 1}"]
        print(f"{name}: {len(seq)} frames, last output range [{last.min():.4f}, {last.max():.4f}]")
    print(f"wrote {os.path.normpath(args.out)}")


if __name__ == "__main__":
    main()
