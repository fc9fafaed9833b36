# SPDX-License-Identifier: Apache-2.0
"""Train a learned baseline (wskpn, nbgd) on afn's data and protocol.

    cd training && /usr/bin/python3 -m afn.baselines.train --method wskpn --data ../data/afn-v2 \\
        --spp 1 --out results/wskpn [--cache results/v2-spp1-cache] [--minutes 40] [--threads 1]

Data, crops (128x128, flips, brightness jitter) and the scene rules (a generated dataset's eval
split is never trained on) are afn.train's; the inputs come from ``afntool --features`` (afn's
features: the baselines read cta, albedo, normal01, depth01). Loss, learning rate and batch follow
each paper (WSKPN: SMAPE eps 0.01, Adam 1e-3; NBGD: L1 on tone-mapped output, Adam 1e-4) except
the batch size, which is sized for a CPU (default 8; the papers: 64 and 1). OUT holds config.json,
log.csv, checkpoints/latest.pt (resumed) and model.afnw (what the C++ method embeds).
"""

import argparse
import os
import time

import numpy as np
import torch

from .. import color, fast_alloc
from ..dataset import KEYS, CropSampler, load_scene, to_tensors
from ..train import RunFolder, git_revision, start_run
from . import archive, nbgd, wskpn

LOSSES = {"wskpn": wskpn.loss, "nbgd": nbgd.loss}
LEARNING_RATES = {"wskpn": 1e-3, "nbgd": 1e-4}


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--method", required=True, choices=archive.METHODS)
    ap.add_argument("-d", "--data", required=True)
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--spp", default="")
    ap.add_argument("--scenes", default="")
    ap.add_argument("--holdout", default="")
    ap.add_argument("--cache", default="", help="folder keeping the prepared scenes as .npz "
                    "(reused by later runs; delete it when the data or afntool change)")
    ap.add_argument("-e", "--epochs", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=50, help="batches per epoch")
    ap.add_argument("-b", "--batch", type=int, default=8)
    ap.add_argument("--lr", type=float, default=0.0, help="0: the paper's")
    ap.add_argument("--crop", type=int, default=128)
    ap.add_argument("--device", default="auto")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--minutes", type=float, default=0.0)
    return ap.parse_args(argv)


def load_cached(name, folder, cache):
    """A prepared scene (afn.dataset.load_scene), kept in ``cache`` as .npz when given."""
    path = os.path.join(cache, name.replace("/", "_") + ".npz") if cache else ""
    if path and os.path.exists(path):
        with np.load(path) as z:
            return {k: z[k] for k in KEYS}
    scene = load_scene(folder)
    if path:
        os.makedirs(cache, exist_ok=True)
        np.savez(path + ".tmp.npz", **scene)
        os.replace(path + ".tmp.npz", path)
    return scene


class BaselineRun(RunFolder):
    def __init__(self, path, method):
        super().__init__(path)
        self.method = method

    def checkpoint(self, model, opt, sampler, epoch, cfg, device):
        tmp = self.latest + ".tmp"
        torch.save({"model": model.state_dict(), "optimizer": opt.state_dict(), "epoch": epoch,
                    "method": self.method, "sampler_rng": sampler.rng.get_state(),
                    "torch_rng": torch.get_rng_state()}, tmp)
        os.replace(tmp, self.latest)
        archive.save_model(self.weights, self.method, model.cpu())
        model.to(device)


def forward(model, b):
    out = model(b["cta"], b["albedo"], b["normal01"], b["depth01"])
    return color.remodulate(out["o"], b["albedo"])


def main(argv=None):
    args = parse_args(argv)
    device, all_scenes, train_names, holdout = start_run(args)
    run = BaselineRun(args.out, args.method)
    lr = args.lr or LEARNING_RATES[args.method]
    run.save_config({**vars(args), "lr": lr, "device": str(device), "train_scenes": train_names,
                     "git": git_revision(), "torch": torch.__version__})
    print(f"loading {len(train_names)} training scenes ...", flush=True)
    train = [load_cached(s, all_scenes[s], args.cache) for s in train_names]
    sampler = CropSampler(train, args.crop, seed=args.seed)
    model = archive.make_model(args.method).to(device)
    opt = torch.optim.Adam(model.parameters(), lr=lr)
    start = run.resume(model, opt, sampler, device)
    loss_fn = LOSSES[args.method]
    t_start = time.time()
    for epoch in range(start, args.epochs):
        t0, losses = time.time(), []
        for _ in range(args.steps):
            b = to_tensors(sampler.batch(args.batch), device)
            loss = loss_fn(forward(model, b), b["target"])
            opt.zero_grad(set_to_none=True)
            loss.backward()
            if not torch.isfinite(loss) or not all(
                    torch.isfinite(p.grad).all() for p in model.parameters() if p.grad is not None):
                continue  # one bad batch never poisons the weights
            opt.step()
            losses.append(loss.item())
        mean = float(np.mean(losses)) if losses else float("nan")
        run.append_log(epoch + 1, mean, float("nan"), float("nan"), time.time() - t0)
        print(f"epoch {epoch + 1}: train loss {mean:.5f} ({time.time() - t0:.1f} s)", flush=True)
        run.checkpoint(model, opt, sampler, epoch + 1, None, device)
        if args.minutes and time.time() - t_start > args.minutes * 60.0:
            print(f"time limit of {args.minutes} minutes reached after epoch {epoch + 1}",
                  flush=True)
            break


if __name__ == "__main__":
    fast_alloc.reexec("afn.baselines.train")  # jemalloc: faster CPU steps (fast_alloc.py)
    main()
