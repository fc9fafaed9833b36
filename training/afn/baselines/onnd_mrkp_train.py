# SPDX-License-Identifier: Apache-2.0
"""Train a learned baseline (ONND or MR-KP) on the same data and protocol as afn (train.py):
a generated dataset's training sequences at the given sample count (its eval split, family
atrium, never trained on), inputs prepared by the C++ core through ``afntool --features``.

    cd training && /usr/bin/python3 -m afn.baselines.onnd_mrkp_train --model mrkp \\
        --data $AFN_DATA/afn-v2 --spp 1 --out results/mrkp [--crop 64] [--minutes 35] [--threads 1]

Budget choices (CPU training; the papers trained for days on GPUs): crops of 64x64 (the papers:
128x128), a wall-clock limit instead of epochs, Adam lr 1e-3 (ONND's; beta2 0.99 for ONND as its
paper), divided by 5 for the last fifth of the time. ONND trains on whole 6-frame sequences (the
recurrence), MR-KP on single frames. Prepared scenes are cached as .npy under OUT/cache (memory-
mapped, so concurrent runs share them). OUT/log.csv has one line per 25 steps; OUT/model.afnw is
the latest weights (metadata ``format=onnd|mrkp``) for the C++ core.
"""

import argparse
import json
import os
import time

import numpy as np
import torch

from .. import fast_alloc
from ..dataset import evaluation_scenes, find_scenes, load_scene
from ..weights import dumps
from . import mrkp, onnd
from .common import SEQ_KEYS, SequenceSampler


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description="Train a learned baseline (onnd, mrkp).")
    ap.add_argument("--model", required=True, choices=("onnd", "mrkp"))
    ap.add_argument("-d", "--data", required=True, help="generated dataset root (afn-dataset-2)")
    ap.add_argument("--spp", default="1", help="input sample count level (default 1)")
    ap.add_argument("-o", "--out", required=True, help="results folder (resumed when it exists)")
    ap.add_argument("--cache", default="", help="folder of prepared .npy arrays (default OUT/cache)")
    ap.add_argument("--crop", type=int, default=64)
    ap.add_argument("-b", "--batch", type=int, default=0, help="0: 4 sequences (onnd), 8 (mrkp)")
    ap.add_argument("--lr", type=float, default=1e-3)
    ap.add_argument("--minutes", type=float, default=35.0, help="wall-clock training budget")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--seed", type=int, default=0)
    return ap.parse_args(argv)


def prepared_scenes(args):
    """List of scene dicts (F, H, W, C) arrays, memory-mapped from the cache (built on first use)."""
    cache = args.cache or os.path.join(args.out, "cache")
    done = os.path.join(cache, "scenes.json")
    if not os.path.exists(done):
        scenes = find_scenes(args.data, args.spp)
        held = evaluation_scenes(args.data, args.spp)
        names = [s for s in scenes if s not in held]
        print(f"preparing {len(names)} training scenes through afntool ...", flush=True)
        arrays = {k: [] for k in SEQ_KEYS}
        for n in names:
            s = load_scene(scenes[n])
            for k in SEQ_KEYS:
                arrays[k].append(s[k])
        os.makedirs(cache, exist_ok=True)
        for k in SEQ_KEYS:
            np.save(os.path.join(cache, f"{k}.npy"), np.stack(arrays[k]))
        with open(done, "w") as f:
            json.dump(names, f)
    with open(done) as f:
        names = json.load(f)
    arrays = {k: np.load(os.path.join(cache, f"{k}.npy"), mmap_mode="r") for k in SEQ_KEYS}
    return [{k: arrays[k][i] for k in SEQ_KEYS} for i in range(len(names))], names


def export(path, model, name):
    meta = {"format": name}
    if name == "onnd":
        meta.update(enc=",".join(map(str, model.enc)), bottleneck=model.bottleneck)
    else:
        meta.update(width=model.width)
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(dumps(model.state_dict(), meta))
    os.replace(tmp, path)


def main(argv=None):
    args = parse_args(argv)
    torch.set_num_threads(args.threads)
    torch.manual_seed(args.seed)
    os.makedirs(args.out, exist_ok=True)
    scenes, names = prepared_scenes(args)
    is_onnd = args.model == "onnd"
    model = onnd.ONND() if is_onnd else mrkp.MRKP()
    cost = (onnd if is_onnd else mrkp).cost_per_pixel(model)
    with open(os.path.join(args.out, "config.json"), "w") as f:
        json.dump({**vars(args), "train_scenes": names, "cost": cost}, f, indent=2)
    betas = (0.9, 0.99) if is_onnd else (0.9, 0.999)
    opt = torch.optim.Adam(model.parameters(), lr=args.lr, betas=betas)
    batch = args.batch or (4 if is_onnd else 8)
    sampler = SequenceSampler(scenes, args.crop, frames=6 if is_onnd else 1, seed=args.seed)
    kernel = onnd.log_kernel()
    latest = os.path.join(args.out, "latest.pt")
    step = 0
    if os.path.exists(latest):
        ck = torch.load(latest)
        model.load_state_dict(ck["model"])
        opt.load_state_dict(ck["optimizer"])
        step = ck["step"]
    log = os.path.join(args.out, "log.csv")
    start, losses, decayed = time.time(), [], False
    while time.time() - start < args.minutes * 60.0:
        if not decayed and time.time() - start > 0.8 * args.minutes * 60.0:
            for g in opt.param_groups:
                g["lr"] = args.lr / 5.0
            decayed = True
        seq = sampler.batch(batch)
        if is_onnd:
            loss = onnd.sequence_loss(model, seq, kernel)
        else:
            loss = mrkp.loss(model, {k: v[0] for k, v in seq.items()})
        opt.zero_grad(set_to_none=True)
        loss.backward()
        if not torch.isfinite(loss):
            continue
        opt.step()
        losses.append(loss.item())
        step += 1
        if step % 25 == 0:
            with open(log, "a") as f:
                f.write(f"{step},{np.mean(losses):.6f},{time.time() - start:.1f}\n")
            print(f"step {step}: loss {np.mean(losses):.5f} ({time.time() - start:.0f} s)",
                  flush=True)
            losses = []
        if step % 100 == 0:
            torch.save({"model": model.state_dict(), "optimizer": opt.state_dict(),
                        "step": step}, latest + ".tmp")
            os.replace(latest + ".tmp", latest)
            export(os.path.join(args.out, "model.afnw"), model, args.model)
    torch.save({"model": model.state_dict(), "optimizer": opt.state_dict(), "step": step}, latest)
    export(os.path.join(args.out, "model.afnw"), model, args.model)
    print(f"done after {step} steps; cost {cost}", flush=True)


if __name__ == "__main__":
    fast_alloc.reexec("afn.baselines.onnd_mrkp_train")  # jemalloc (fast_alloc.py)
    main()
