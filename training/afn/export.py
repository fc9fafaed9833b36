# SPDX-License-Identifier: Apache-2.0
"""Export a training checkpoint to the weights archive (.afnw) that the C++ core embeds or loads.

    cd training && /usr/bin/python3 -m afn.export results/NAME [-o ../weights/afn.afnw]

The architecture comes from the checkpoint (never from flags). The written archive is read back
and compared with the checkpoint before the command succeeds.
"""

import argparse
import os

import torch

from .model import AFNConfig, make_model
from .weights import load_model, save_model


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", help="results folder of afn.train (or a .pt checkpoint)")
    ap.add_argument("-o", "--output", default="", help="output .afnw (default: RESULTS/model.afnw)")
    args = ap.parse_args(argv)
    ck_path = args.results if args.results.endswith(".pt") else \
        os.path.join(args.results, "checkpoints", "latest.pt")
    ck = torch.load(ck_path, map_location="cpu")
    model = make_model(AFNConfig.from_dict(ck["config"]))
    model.load_state_dict(ck["model"])
    out = args.output or os.path.join(os.path.dirname(os.path.dirname(ck_path)), "model.afnw")
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    save_model(out, model)
    back = load_model(out)
    for k, v in model.state_dict().items():
        if not torch.equal(v, back.state_dict()[k]):
            raise SystemExit(f"afn.export: {out}: tensor {k} did not round-trip")
    print(f"wrote {out} ({os.path.getsize(out)} bytes, epoch {ck['epoch']}, "
          f"variant {model.cfg.variant})")


if __name__ == "__main__":
    main()
