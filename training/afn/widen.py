# SPDX-License-Identifier: Apache-2.0
"""Widen a trained AFN model without changing what it computes, so that training can go on with
more channels instead of starting from scratch.

    cd training && /usr/bin/python3 -m afn.widen ../weights/afn.afnw --enc 24,48,96 --dec 48,36 \\
        -o results/wide/init.afnw
    /usr/bin/python3 -m afn.train ... --enc 24,48,96 --dec 48,36 --init results/wide/init.afnw

Every convolution of the wider model keeps the old weights in the block of old input and output
channels. The added output channels (new units) get PyTorch's default initialisation for their
weights from the old inputs and their bias, and every weight *from* an added channel is zero: the
new units compute something, but nothing reads it yet, so the wider model's output equals the old
one's (up to float rounding). Training then moves the zero weights first (their gradient is the
new units' activation times the output's gradient) and the new units start to matter. This is the
zero-initialised variant of function-preserving growth (Net2Net, Chen, Goodfellow & Shlens 2016,
splits duplicated units instead; duplicates need noise to break their symmetry).

Only the ``full``/``fusion``/``1spp``/``ta`` variants (model.py) widen; the network's output
channels (49 kernel taps, the fusion weight, RGB) never change, and its inputs grow only by the
history input (``--history``: the 14th input channel of model.py, its weights zero, so the grown
model computes what the old one did whatever history01 holds):

    /usr/bin/python3 -m afn.widen ../weights/afn.afnw --history -o results/history/init.afnw
"""

import argparse

import torch

from .model import KERNEL_TAPS, REFINE_INPUT_CHANNELS, AFN, AFNConfig, input_channels
from .weights import load_model, save_model


def _segments(cfg):
    """Per convolution: (input segments, output width) of cfg; a concatenated input is a list of
    segment widths in the order model.py concatenates them."""
    c1, c2, c3 = cfg.enc
    d2, d1 = cfg.dec
    r = cfg.refine
    x = input_channels(cfg)
    trust = {"headG": ([c1], 1)} if cfg.albedo_trust else {}
    return {**trust, "enc1": ([x], c1), "enc2": ([c1], c2), "enc3": ([c2], c3),
            "dec2": ([c3, c2], d2), "dec1": ([d2, c1], d1), "head1": ([d1], KERNEL_TAPS),
            "headTA": ([d1, x], KERNEL_TAPS + 1),
            "ref1": ([REFINE_INPUT_CHANNELS], r), "ref2": ([r], r), "ref3": ([r], 3),
            "head4": ([d2], KERNEL_TAPS + 1)}


def widen(model, enc=None, dec=None, refine=None, seed=0, history=None, albedo_trust=None):
    """A wider copy of `model` (model.AFN) with the same output; widths not given stay, and
    ``history=True`` adds the history input (None: as the model). ``albedo_trust=True`` adds the
    learned albedo trust (model.py), whose head starts at t = 0.0025: almost the same output.

    Raises:
        ValueError: a width smaller than the model's, or the history input taken away (only
            growth preserves the function).
    """
    old = model.cfg
    history = old.history if history is None else bool(history)
    if old.history and not history:
        raise ValueError("the model has the history input: only growth keeps what it computes")
    albedo_trust = old.albedo_trust if albedo_trust is None else bool(albedo_trust)
    if old.albedo_trust and not albedo_trust:
        raise ValueError("the model has the albedo trust: only growth keeps what it computes")
    cfg = AFNConfig(variant=old.variant, enc=tuple(enc or old.enc), dec=tuple(dec or old.dec),
                    refine=int(refine or old.refine), inputs=old.inputs, spp=old.spp,
                    quarter=old.quarter, history=history, albedo_trust=albedo_trust)
    for name, a, b in (("enc", old.enc, cfg.enc), ("dec", old.dec, cfg.dec),
                       ("refine", (old.refine,), (cfg.refine,))):
        if len(a) != len(b) or any(y < x for x, y in zip(a, b)):
            raise ValueError(f"--{name} {','.join(map(str, b))} is narrower than the model's "
                             f"{','.join(map(str, a))}: only widening keeps what it computes")
    torch.manual_seed(seed)
    wide = AFN(cfg)
    old_state, new_state = model.state_dict(), wide.state_dict()
    old_seg, new_seg = _segments(old), _segments(cfg)
    with torch.no_grad():
        for conv, (new_in, new_out) in new_seg.items():
            if conv + ".weight" not in new_state or conv not in old_seg:
                continue                # a variant without refinement; a head the model lacks
            old_in, old_out = old_seg[conv]
            w, b = new_state[conv + ".weight"], new_state[conv + ".bias"]
            ow = old_state[conv + ".weight"]
            start_new = start_old = 0
            for seg_old, seg_new in zip(old_in, new_in):
                w[:, start_new + seg_old:start_new + seg_new] = 0.0     # weights from added inputs
                w[:old_out, start_new:start_new + seg_old] = ow[:, start_old:start_old + seg_old]
                start_new += seg_new
                start_old += seg_old
            b[:old_out] = old_state[conv + ".bias"]
    wide.load_state_dict(new_state)
    return wide


def _widths(text):
    return tuple(int(v) for v in text.split(",")) if text else None


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m afn.widen", description=__doc__.split("\n\n")[0])
    ap.add_argument("weights", help="a trained AFN model (.afnw)")
    ap.add_argument("-o", "--out", required=True, help="the widened model (.afnw)")
    ap.add_argument("--enc", default="", help="new encoder widths e1,e2,e3 (default: unchanged)")
    ap.add_argument("--dec", default="", help="new decoder widths d2,d1 (default: unchanged)")
    ap.add_argument("--refine", type=int, default=0, help="new refinement width (default: unchanged)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the added units' initialisation")
    ap.add_argument("--history", action="store_true",
                    help="add the history input (model.py; zero weights: the same output)")
    ap.add_argument("--albedo-trust", action="store_true",
                    help="add the learned albedo trust (model.py; starts at a colour-space share "
                         "of 0.0025: almost the same output)")
    args = ap.parse_args(argv)
    model = load_model(args.weights)
    if not isinstance(model, AFN):
        raise SystemExit(f"afn.widen: {args.weights} is not an AFN model (AFN large does not widen)")
    try:
        wide = widen(model, _widths(args.enc), _widths(args.dec), args.refine or None, args.seed,
                     history=True if args.history else None,
                     albedo_trust=True if args.albedo_trust else None)
    except ValueError as e:
        raise SystemExit(f"afn.widen: {e}")
    save_model(args.out, wide)
    n_old = sum(p.numel() for p in model.parameters())
    n_new = sum(p.numel() for p in wide.parameters())
    print(f"{args.weights}: {n_old} parameters -> {args.out}: {n_new} parameters")


if __name__ == "__main__":
    main()
