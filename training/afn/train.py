# SPDX-License-Identifier: Apache-2.0
"""Train an AFN model (paper Sec. IV-B): SMAPE on the remodulated output, 128x128 crops, random
flips, brightness jitter [0.8, 1.2], Adam lr 1e-3, batch 16.

    cd training && /usr/bin/python3 -m afn.train --data DATA --out results/NAME \\
        [--holdout moving_light,glass] [--variant full] [--epochs 300] [--device auto]

Re-running the same command resumes from OUT/checkpoints/latest.pt. OUT/config.json holds the
resolved configuration (with the git revision), OUT/log.csv one line per epoch (train SMAPE,
validation PSNR/SMAPE on the held-out scenes, seconds), OUT/model.afnw the latest weights in the
archive format the C++ core reads (and, with --keep-epochs N, OUT/epochs/E<epoch>.afnw those of
the last N epochs, for afn.average). The device comes from --device (auto: CUDA when available), so
the same code runs on a CPU here and on a GPU with a newer PyTorch.
"""

import argparse
import hashlib
import json
import math
import os
import re
import shutil
import subprocess
import time

import numpy as np
import torch

from . import color, fast_alloc, input_sets
from .afntool import AfntoolError
from .dataset import (KEYS, LAYOUT, CropSampler, SceneError, evaluation_scenes, find_scenes,
                      load_scene, to_tensors)
from .generated import expand
from .loss import smape, temporal_gradient
from .model import VARIANTS, AFNConfig, make_model
from .weights import load_model, save_model


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description="Train the AFN denoiser.")
    ap.add_argument("-d", "--data", required=True, help="dataset root (scene folders) or one scene")
    ap.add_argument("-o", "--out", required=True, help="results folder (resumed when it exists)")
    ap.add_argument("--scenes", default="", help="comma list of training scenes (default: all "
                    "not held out); in a generated dataset FAMILY-SEED names all its --spp levels")
    ap.add_argument("--holdout", default="", help="comma list of validation scenes, never trained on")
    ap.add_argument("--spp", default="", help="input sample counts of a generated dataset "
                    "(afn-dataset-2), e.g. 1 or 16,64: its spp<S> folders are the scenes")
    ap.add_argument("--variant", default="full", choices=VARIANTS, help="ablation variant, or large (AFN large, model_large.py: no TA "
                    "input, for high --spp)")
    ap.add_argument("--enc", default="16,32,64", help="encoder widths e1,e2,e3")
    ap.add_argument("--dec", default="32,24", help="decoder widths d2,d1")
    ap.add_argument("--refine", type=int, default=16, help="refinement width")
    ap.add_argument("--history", action="store_true",
                    help="add the history input (model.py: 1 / the frames the TA input holds, a "
                         "14th input channel; grow a trained model with afn.widen --history and "
                         "pass it as --init)")
    ap.add_argument("--albedo-trust", action="store_true",
                    help="add the learned albedo trust (model.py: a per-pixel share of "
                         "colour-space filtering; grow a trained model with afn.widen "
                         "--albedo-trust and pass it as --init)")
    ap.add_argument("--quarter", action="store_true", help="add the quarter-resolution scale "
                    "(model.py; full and fusion only); with --init from a model without it, the "
                    "new head starts almost neutral")
    ap.add_argument("-e", "--epochs", type=int, default=300, help="epochs (paper: 300)")
    ap.add_argument("--steps", type=int, default=0, help="batches per epoch (0: one crop per "
                    "128x128 area of every training frame / batch size)")
    ap.add_argument("-b", "--batch", type=int, default=16, help="batch size (paper: 16)")
    ap.add_argument("--lr", type=float, default=1e-3, help="Adam learning rate (paper: 1e-3)")
    ap.add_argument("--lr-end", type=float, default=-1.0, help="anneal the learning rate along "
                    "a cosine from --lr at epoch 1 to this value after --epochs (per epoch, so a "
                    "resumed run continues the same schedule); < 0: constant --lr (the paper)")
    ap.add_argument("--crop", type=int, default=128, help="crop size (paper: 128)")
    ap.add_argument("--keep-epochs", type=int, default=0, help="also keep the weights of the "
                    "last N epochs as OUT/epochs/E<epoch>.afnw (for afn.average; 0: none)")
    ap.add_argument("--temporal-weight", type=float, default=0.0, help="weight of a temporal "
                    "term added to SMAPE (loss.temporal_gradient; 0: the paper's loss): each batch "
                    "is then batch/2 pairs of consecutive frames, the same crops in both")
    ap.add_argument("--max-frames", type=int, default=0, help="frames per scene (0: all)")
    ap.add_argument("--val-frames", type=int, default=4, help="validation frames per held-out "
                    "scene (evenly spaced; 0: all)")
    ap.add_argument("--device", default="auto", help="auto, cpu, cuda, cuda:1, ...")
    ap.add_argument("--threads", type=int, default=0, help="CPU threads (0: PyTorch default)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--minutes", type=float, default=0.0, help="stop after the epoch that passes "
                    "this many minutes of this run (0: no limit; a rerun resumes and continues)")
    ap.add_argument("--train-only", default="", help="comma list of parameter-name prefixes "
                    "(e.g. head4): only those are trained, the rest stays as --init gave it "
                    "(growing a trained model by a new part; default: train everything)")
    ap.add_argument("--init", default="", help="start a new run from these weights (.afnw or a "
                    "checkpoint .pt; same architecture), e.g. to fine-tune the shipped model from an "
                    "evaluation model")
    ap.add_argument("--aov", action="append", default=[], metavar="ROLE=CHANNELS",
                    help="map a pass the C++ core's automatic role mapping misses, as afntool's "
                    "--aov (e.g. albedo=diffuse.R,diffuse.G,diffuse.B); repeatable")
    ap.add_argument("--cache", default="", help="keep the prepared scenes in this folder and "
                    "reuse them (runs for several --inputs share the afntool preparation)")
    ap.add_argument("--inputs", default=input_sets.FULL, help="input set the model is for: "
                    "color, or a list of albedo, normal, depth, temporal (default: "
                    "all); the other inputs are held at their neutral values in the training data "
                    "(input_sets.mask, as the C++ filter does) and the set is stored in the weights")
    args = ap.parse_args(argv)
    try:
        args.inputs = input_sets.parse(args.inputs)
    except ValueError as e:
        ap.error(f"--inputs: {e}")
    return args


def resolve_device(name):
    if name == "auto":
        return torch.device("cuda" if torch.cuda.is_available() else "cpu")
    return torch.device(name)


def git_revision():
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True,
                              cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    except OSError:
        return ""


def forward(model, batch):
    extra = (batch["history01"],) if getattr(model.cfg, "history", False) else ()
    out = model(batch["c1"], batch["cta"], batch["albedo"], batch["normal01"], batch["depth01"],
                *extra)
    return color.remodulate(out["o"], batch["albedo"])


def psnr_tonemapped(a, b):
    """PSNR (dB) of T(a) vs T(b), T = clip(max(x,0)^(1/2.2), 0, 1)."""
    mse = torch.mean((color.tonemap(a) - color.tonemap(b)) ** 2).item()
    return 10.0 * np.log10(1.0 / max(mse, 1e-12))


@torch.no_grad()
def validate(model, scenes, device, frames):
    model.eval()
    psnrs, smapes = [], []
    for s in scenes:
        n = s["c1"].shape[0]
        idx = range(n) if frames <= 0 else np.linspace(0, n - 1, min(frames, n)).astype(int)
        for f in idx:
            t = to_tensors({k: v[f] for k, v in s.items()}, device)
            out = forward(model, t)
            psnrs.append(psnr_tonemapped(out, t["target"]))
            smapes.append(smape(out, t["target"]).item())
    model.train()
    return (float(np.mean(psnrs)), float(np.mean(smapes))) if psnrs else (float("nan"),) * 2


def trainable_parameters(model, only):
    """The parameters to train: all, or (``only``, a comma list of name prefixes) just those whose
    name starts with one of them; the others get requires_grad=False and never change."""
    prefixes = tuple(p.strip() for p in only.split(",") if p.strip())
    if not prefixes:
        return list(model.parameters())
    chosen = []
    for name, p in model.named_parameters():
        p.requires_grad_(name.startswith(prefixes))
        if p.requires_grad:
            chosen.append(p)
    if not chosen:
        raise SystemExit(f"afn.train: --train-only {only}: no parameter of the model has that name")
    return chosen


def init_weights(model, path, device):
    """Load a state_dict from a .afnw archive or a training checkpoint into ``model``: every tensor
    the model has (same name, same shape required); tensors the source lacks (e.g. the refinement
    when going from the "fusion" variant to "full") keep their fresh initialisation."""
    if path.endswith(".afnw"):
        state = load_model(path).state_dict()
    else:
        state = torch.load(path, map_location=device)["model"]
    own = model.state_dict()
    shared = {k: v for k, v in state.items() if k in own}
    for k, v in shared.items():
        if v.shape != own[k].shape:
            raise RuntimeError(f"--init {path}: {k} has shape {tuple(v.shape)}, the model "
                               f"{tuple(own[k].shape)}")
    if not shared:
        raise RuntimeError(f"--init {path}: no tensor in common with this model")
    # Another ablation variant shares the kernel-prediction tensors; the rest keeps its init.
    model.load_state_dict(shared, strict=False)
    fresh = sorted(set(own) - set(shared))
    if fresh:
        print(f"--init: {len(shared)} tensors loaded, {len(fresh)} freshly initialised: "
              f"{', '.join(fresh)}", flush=True)


def resolve_scenes(args):
    """(all scenes by name, training names, held-out names) from the arguments; SystemExit on a
    contradiction (unknown scene, a scene both trained on and held out, an evaluation scene of a
    generated dataset trained on, none left)."""
    try:
        all_scenes = find_scenes(args.data, args.spp or None)
        evals = evaluation_scenes(args.data, args.spp or None)
        holdout = expand([s for s in args.holdout.split(",") if s], all_scenes)
        chosen = expand([s for s in args.scenes.split(",") if s], all_scenes)
    except ValueError as e:
        raise SystemExit(f"afn.train: {e}")
    except KeyError as e:
        raise SystemExit(f"afn.train: scene {e} not in {args.data}")
    train_names = chosen or [s for s in all_scenes if s not in holdout and s not in evals]
    if set(train_names) & set(holdout):
        raise SystemExit("afn.train: a scene is both trained on and held out")
    if set(train_names) & evals:
        raise SystemExit("afn.train: evaluation scenes of a generated dataset are never trained on")
    if not train_names:
        where = args.data if os.path.isdir(args.data) else f"{args.data} (not a folder)"
        held = f" ({len(holdout)} held out)" if holdout else ""
        raise SystemExit(f"afn.train: no training scenes in {where}{held}: {LAYOUT}")
    return all_scenes, train_names, holdout


def start_run(args):
    """The start every training run shares: the device (resolve_device), torch's thread count
    and seed from the arguments, then the scenes (resolve_scenes).
    Returns (device, all scenes by name, training names, held-out names)."""
    device = resolve_device(args.device)
    if args.threads:
        torch.set_num_threads(args.threads)
    torch.manual_seed(args.seed)
    return (device, *resolve_scenes(args))


def cached_scene(args, path, name, max_frames):
    """load_scene, through ``--cache DIR`` when given: the prepared full-set features of a scene
    are kept as DIR/<name>.npz (keyed by the --aov list and frame count) and reused by later runs,
    e.g. the models for several input sets trained from the same data."""
    if not args.cache:
        return load_scene(path, max_frames=max_frames, aov=args.aov)
    # The key names the features' layout (dataset.KEYS) too: a cache of another layout is not
    # read as this one.
    key = hashlib.sha1(repr((sorted(args.aov), max_frames, KEYS)).encode()).hexdigest()[:10]
    file = os.path.join(args.cache, f"{name.replace('/', '__')}-{key}.npz")
    if os.path.exists(file):
        with np.load(file) as z:
            return {k: z[k] for k in z.files}
    scene = load_scene(path, max_frames=max_frames, aov=args.aov)
    os.makedirs(args.cache, exist_ok=True)
    tmp = file + f".{os.getpid()}.tmp.npz"
    np.savez(tmp, **scene)
    os.replace(tmp, file)
    return scene


def model_config(args):
    """The AFNConfig the arguments describe."""
    # The sample count the archive declares (lib/core/methods/afn/model_set.h picks the model
    # nearest a frame's count): the lowest level trained on, 1 for folders without levels.
    spp = min(int(v) for v in args.spp.split(",") if v.strip()) if args.spp.strip() else 1
    return AFNConfig(variant=args.variant, enc=tuple(int(v) for v in args.enc.split(",")),
                     dec=tuple(int(v) for v in args.dec.split(",")), refine=args.refine,
                     inputs=args.inputs, spp=spp, quarter=args.quarter, history=args.history,
                     albedo_trust=args.albedo_trust)


class RunFolder:
    """A self-describing results folder: config.json, log.csv (one line per epoch),
    checkpoints/latest.pt (resume point) and model.afnw (the latest weights for the C++ core)."""

    def __init__(self, path):
        self.path = path
        self.latest = os.path.join(path, "checkpoints", "latest.pt")
        self.log = os.path.join(path, "log.csv")
        self.weights = os.path.join(path, "model.afnw")
        self.epochs = os.path.join(path, "epochs")
        os.makedirs(os.path.dirname(self.latest), exist_ok=True)

    def save_config(self, config):
        with open(os.path.join(self.path, "config.json"), "w") as f:
            json.dump(config, f, indent=2)

    def resume(self, model, opt, sampler, device):
        """Restore the latest checkpoint if there is one; returns the epoch to start from."""
        if not os.path.exists(self.latest):
            return 0
        ck = torch.load(self.latest, map_location=device)
        model.load_state_dict(ck["model"])
        opt.load_state_dict(ck["optimizer"])
        sampler.rng.set_state(ck["sampler_rng"])
        torch.set_rng_state(ck["torch_rng"])
        print(f"resumed from {self.latest} after epoch {ck['epoch']}", flush=True)
        return ck["epoch"]

    def append_log(self, epoch, train_smape, val_psnr, val_smape, seconds):
        if not os.path.exists(self.log):
            with open(self.log, "w") as f:
                f.write("epoch,train_smape,val_psnr,val_smape,seconds\n")
        with open(self.log, "a") as f:
            f.write(f"{epoch},{train_smape:.6f},{val_psnr:.4f},{val_smape:.6f},{seconds:.1f}\n")

    def checkpoint(self, model, opt, sampler, epoch, cfg, device):
        """Write latest.pt atomically and export model.afnw."""
        tmp = self.latest + ".tmp"
        torch.save({"model": model.state_dict(), "optimizer": opt.state_dict(), "epoch": epoch,
                    "config": cfg.to_dict(), "sampler_rng": sampler.rng.get_state(),
                    "torch_rng": torch.get_rng_state()}, tmp)
        os.replace(tmp, self.latest)
        save_model(self.weights, model.cpu())
        model.to(device)

    def keep_epoch(self, epoch, keep):
        """Copy model.afnw to epochs/E<epoch>.afnw and delete all but the last `keep` of them,
        so that averaging the last N epochs (afn.average OUT/epochs/*.afnw) is one command."""
        os.makedirs(self.epochs, exist_ok=True)
        tmp = os.path.join(self.epochs, f".E{epoch:04d}.afnw.tmp")
        shutil.copyfile(self.weights, tmp)
        os.replace(tmp, os.path.join(self.epochs, f"E{epoch:04d}.afnw"))
        kept = sorted((f for f in os.listdir(self.epochs) if re.fullmatch(r"E\d{4,}\.afnw", f)),
                      key=lambda f: int(f[1:-5]))
        for old in kept[:-keep]:
            os.remove(os.path.join(self.epochs, old))


def epoch_lr(args, epoch):
    """Learning rate of (0-based) epoch: --lr, or the cosine from --lr to --lr-end over --epochs.
    A fine-tune of a few thousand steps ends nearer a minimum when the rate falls at its end
    (SGDR, Loshchilov & Hutter 2017); the paper trains at a constant 1e-3."""
    if args.lr_end < 0 or args.epochs <= 1:
        return args.lr
    t = min(max(epoch / (args.epochs - 1), 0.0), 1.0)
    return args.lr_end + 0.5 * (args.lr - args.lr_end) * (1.0 + math.cos(math.pi * t))


def train_epoch(model, opt, sampler, steps, batch, device, temporal_weight=0.0):
    """One epoch of SMAPE steps (+ temporal_weight x the temporal term on batch/2 frame pairs);
    returns (mean SMAPE, batches skipped as non-finite)."""
    losses, skipped = [], 0
    for _ in range(steps):
        if temporal_weight > 0:
            b = to_tensors(sampler.pair_batch(max(batch // 2, 1)), device)
            out = forward(model, b)
            spatial = smape(out, b["target"])
            loss = spatial + temporal_weight * temporal_gradient(out, b["target"])
        else:
            b = to_tensors(sampler.batch(batch), device)
            spatial = loss = smape(forward(model, b), b["target"])
        opt.zero_grad(set_to_none=True)
        loss.backward()
        grads_ok = all(torch.isfinite(p.grad).all() for p in model.parameters()
                       if p.grad is not None)
        if not (torch.isfinite(loss) and grads_ok):
            skipped += 1          # never let one bad batch poison the weights
            continue
        opt.step()
        losses.append(spatial.item())      # the log's train_smape: SMAPE alone
    return (float(np.mean(losses)) if losses else float("nan")), skipped


def main(argv=None):
    args = parse_args(argv)
    device, all_scenes, train_names, holdout = start_run(args)
    cfg = model_config(args)
    run = RunFolder(args.out)
    run.save_config({**vars(args), "device": str(device), "model": cfg.to_dict(),
                     "train_scenes": train_names, "holdout_scenes": holdout,
                     "git": git_revision(), "torch": torch.__version__})

    mf = args.max_frames or None
    print(f"loading {len(train_names)} training and {len(holdout)} held-out scenes ...", flush=True)
    try:
        def prepared(name):
            return input_sets.mask(cached_scene(args, all_scenes[name], name, mf), args.inputs)
        train = [prepared(s) for s in train_names]
        val = [prepared(s) for s in holdout]
    except (SceneError, AfntoolError) as e:
        raise SystemExit(f"afn.train: {e}")
    sampler = CropSampler(train, args.crop, seed=args.seed)
    area = sum(s["c1"].shape[0] * s["c1"].shape[1] * s["c1"].shape[2] for s in train)
    steps = args.steps or max(1, area // (args.crop * args.crop) // args.batch)

    model = make_model(cfg).to(device)
    opt = torch.optim.Adam(trainable_parameters(model, args.train_only), lr=args.lr)
    start = run.resume(model, opt, sampler, device)
    if start == 0 and args.init:
        init_weights(model, args.init, device)
        print(f"initialised from {args.init}", flush=True)

    run_start = time.time()
    for epoch in range(start, args.epochs):
        t0 = time.time()
        lr = epoch_lr(args, epoch)
        for group in opt.param_groups:
            group["lr"] = lr
        loss, skipped = train_epoch(model, opt, sampler, steps, args.batch, device,
                                    args.temporal_weight)
        vp, vs = validate(model, val, device, args.val_frames)
        dt = time.time() - t0
        run.append_log(epoch + 1, loss, vp, vs, dt)
        print(f"epoch {epoch + 1}/{args.epochs}: lr {lr:.2e}, train SMAPE {loss:.5f}, "
              f"val PSNR {vp:.3f} dB, val SMAPE {vs:.5f} ({dt:.1f} s)"
              + (f", {skipped} non-finite batches skipped" if skipped else ""), flush=True)
        run.checkpoint(model, opt, sampler, epoch + 1, cfg, device)
        if args.keep_epochs > 0:
            run.keep_epoch(epoch + 1, args.keep_epochs)
        if args.minutes and time.time() - run_start > args.minutes * 60.0:
            print(f"time limit of {args.minutes} minutes reached after epoch {epoch + 1}", flush=True)
            break


if __name__ == "__main__":
    fast_alloc.reexec("afn.train")  # jemalloc: 5-10x faster CPU steps here (fast_alloc.py)
    main()
