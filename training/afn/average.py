# SPDX-License-Identifier: Apache-2.0
"""Average the weights of several models of one architecture (checkpoint averaging).

    cd training && /usr/bin/python3 -m afn.average a.afnw b.afnw ... -o averaged.afnw

The mean of the weights of the last epochs of a run whose learning rate has fallen (Polyak
averaging; "stochastic weight averaging", Izmailov et al. 2018) lies nearer the middle of the
minimum the run circles in than any one epoch's weights. The inputs must share the architecture
and the metadata the C++ core reads (variant, input set, sample count); the output keeps them.
Accept an average only where the held-out evaluation says it is better (docs/afn-evaluation.md).
"""

import argparse
import os

import torch

from .weights import load_model, save_model


def average(paths):
    """The model whose every tensor is the mean of the models at ``paths``."""
    if not paths:
        raise ValueError("afn.average: no models given")
    models = [load_model(p) for p in paths]
    first = models[0]
    for p, m in zip(paths[1:], models[1:]):
        if m.cfg.to_dict() != first.cfg.to_dict():
            raise ValueError(f"afn.average: {p}: another architecture or metadata than {paths[0]} "
                             f"({m.cfg.to_dict()} against {first.cfg.to_dict()})")
    states = [m.state_dict() for m in models]
    mean = {k: torch.mean(torch.stack([s[k].double() for s in states]), 0).to(v.dtype)
            for k, v in states[0].items()}
    first.load_state_dict(mean)
    return first


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("models", nargs="+", help=".afnw files of one architecture")
    ap.add_argument("-o", "--output", required=True, help="averaged .afnw")
    args = ap.parse_args(argv)
    try:
        model = average(args.models)
    except (ValueError, OSError) as e:
        raise SystemExit(str(e))
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    tmp = args.output + ".tmp"
    save_model(tmp, model)
    os.replace(tmp, args.output)
    print(f"wrote {args.output}: mean of {len(args.models)} models (variant {model.cfg.variant})")


if __name__ == "__main__":
    main()
