# SPDX-License-Identifier: Apache-2.0
"""Training data: rendered sequences (training/render-dataset, docs/dataset.md) read through
OpenImageIO, turned into the AFN inputs exactly as the C++ "afn" filter prepares them:

    colour    Combined RGB, non-finite -> 0, negatives -> 0 (the core's gather)
    albedo    Denoising Albedo clamped to [0, 1]; normals normalised (zero stays zero), as the gather
    c1        colour / max(albedo, 2^-10)                      (color.demodulate)
    cta       BMFR TA of c1 (ta.py) with Vector motion (y up in Blender -> negated), Position, Normal
    normal01  world Normal * 0.5 + 0.5;  depth01: planar Depth, per-frame min-max (color.py)
    target    reference.NNNN.exr RGB (full radiance, albedo included)

A scene folder holds frame.NNNN.exr and reference.NNNN.exr; a dataset root holds scene folders
(and a manifest.json). Whole scenes are prepared once and kept in memory as float32 arrays;
:class:`CropSampler` draws 128x128 crops with random flips and brightness jitter in [0.8, 1.2].
"""

import glob
import os
import re

import numpy as np
import torch

from . import color
from .ta import TemporalAccumulator

FRAME_RE = re.compile(r"frame\.(\d+)\.exr$")
KEYS = ("c1", "cta", "albedo", "normal01", "depth01", "target")


def _read_channels(path, names):
    """Read the named channels (matched by suffix, e.g. 'Combined.R') into (H, W, len(names))."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise OSError(f"cannot open {path}: {oiio.geterror()}")
    try:
        spec = inp.spec()
        all_names = list(spec.channelnames)
        pixels = inp.read_image(0, spec.nchannels, "float")
    finally:
        inp.close()
    if pixels is None:
        raise OSError(f"cannot read {path}")
    pixels = np.asarray(pixels, np.float32).reshape(spec.height, spec.width, spec.nchannels)
    idx = []
    for n in names:
        hits = [i for i, c in enumerate(all_names) if c == n or c.endswith("." + n)]
        if not hits:
            raise KeyError(f"{path}: no channel '{n}' (has: {', '.join(all_names)})")
        idx.append(hits[0])
    return pixels[..., idx]


def _rgb(path, layer):
    return _read_channels(path, [f"{layer}.{c}" for c in "RGB"])


def _reference_rgb(path):
    try:
        return _rgb(path, "Combined")
    except KeyError:
        return _read_channels(path, ["R", "G", "B"])


def _unit(n):
    """Normalise like the core's gather: n * (1 / |n|) if |n| > 1e-12, else 0 (float32)."""
    n = n.astype(np.float32)
    length = np.sqrt(n[..., 0] * n[..., 0] + n[..., 1] * n[..., 1] + n[..., 2] * n[..., 2])
    inv = np.where(length > 1e-12, np.float32(1) / np.maximum(length, np.float32(1e-30)), 0)
    return (n * inv.astype(np.float32)[..., None]).astype(np.float32)


def frame_numbers(scene_dir):
    """Sorted frame numbers that have both a noisy frame and a reference."""
    nums = []
    for f in glob.glob(os.path.join(scene_dir, "frame.*.exr")):
        m = FRAME_RE.search(f)
        if m and os.path.exists(os.path.join(scene_dir, f"reference.{m.group(1)}.exr")):
            nums.append(m.group(1))
    return sorted(nums)


def load_scene(scene_dir, alpha_min=0.2, max_frames=None):
    """Prepare every frame of one scene (in order, TA needs the history).

    Returns:
        dict of numpy arrays, each (F, H, W, C) float32, keys :data:`KEYS`.
    """
    nums = frame_numbers(scene_dir)[:max_frames]
    if not nums:
        raise FileNotFoundError(f"{scene_dir}: no frame.NNNN.exr with a reference.NNNN.exr")
    ta = TemporalAccumulator(alpha_min=alpha_min)
    out = {k: [] for k in KEYS}
    for n in nums:
        path = os.path.join(scene_dir, f"frame.{n}.exr")
        col = _rgb(path, "Combined")
        col = np.where(np.isfinite(col), np.maximum(col, 0), 0).astype(np.float32)
        alb = np.nan_to_num(_rgb(path, "Denoising Albedo"), nan=0.0, posinf=0.0, neginf=0.0)
        alb = np.clip(alb, 0.0, 1.0)                       # the core's gather clamps albedo
        nrm = _unit(np.nan_to_num(_read_channels(path, ["Normal.X", "Normal.Y", "Normal.Z"])))
        pos = np.nan_to_num(_read_channels(path, ["Position.X", "Position.Y", "Position.Z"]))
        depth = _read_channels(path, ["Depth.Z"])[..., 0]
        vec = np.nan_to_num(_read_channels(path, ["Vector.X", "Vector.Y"]))
        motion = np.stack([vec[..., 0], -vec[..., 1]], -1)   # Blender y up -> rows (y down)
        c1 = color.demodulate(col, alb)
        cta, _ = ta.accumulate(c1, motion=motion, position=pos, normal=nrm)
        out["c1"].append(c1)
        out["cta"].append(cta)
        out["albedo"].append(alb)
        out["normal01"].append(color.normal_to_unit_range(nrm))
        out["depth01"].append(color.depth_to_unit_range(depth)[..., None])
        out["target"].append(_reference_rgb(os.path.join(scene_dir, f"reference.{n}.exr")))
    return {k: np.stack(v).astype(np.float32) for k, v in out.items()}


def find_scenes(root):
    """Scene folders under a dataset root (or the root itself if it is a scene)."""
    if frame_numbers(root):
        return {os.path.basename(os.path.normpath(root)): root}
    return {d: os.path.join(root, d) for d in sorted(os.listdir(root))
            if os.path.isdir(os.path.join(root, d)) and frame_numbers(os.path.join(root, d))}


def to_tensors(sample, device="cpu"):
    """(H, W, C) numpy dict -> (1, C, H, W) tensors (or (B, ...) from (B, H, W, C))."""
    out = {}
    for k, v in sample.items():
        t = torch.from_numpy(np.ascontiguousarray(v))
        t = t[None] if t.dim() == 3 else t
        out[k] = t.permute(0, 3, 1, 2).contiguous().to(device)
    return out


class CropSampler:
    """Random training crops from prepared scenes (paper: 128x128, flips, brightness [0.8, 1.2]).

    Frames smaller than the crop are zero-padded (WSKPN pads before cropping).
    """

    def __init__(self, scenes, crop=128, seed=0):
        self.scenes = list(scenes)
        self.crop = crop
        self.rng = np.random.RandomState(seed)

    def sample(self):
        s = self.scenes[self.rng.randint(len(self.scenes))]
        f = self.rng.randint(s["c1"].shape[0])
        h, w = s["c1"].shape[1:3]
        y = self.rng.randint(max(h - self.crop, 0) + 1)
        x = self.rng.randint(max(w - self.crop, 0) + 1)
        out = {}
        for k in KEYS:
            a = s[k][f, y:y + self.crop, x:x + self.crop]
            if a.shape[0] < self.crop or a.shape[1] < self.crop:
                a = np.pad(a, ((0, self.crop - a.shape[0]), (0, self.crop - a.shape[1]), (0, 0)))
            out[k] = a
        if self.rng.rand() < 0.5:
            out = {k: v[:, ::-1] for k, v in out.items()}
        if self.rng.rand() < 0.5:
            out = {k: v[::-1] for k, v in out.items()}
        gain = np.float32(self.rng.uniform(0.8, 1.2))
        for k in ("c1", "cta", "target"):
            out[k] = out[k] * gain
        return {k: np.ascontiguousarray(v, np.float32) for k, v in out.items()}

    def batch(self, n):
        items = [self.sample() for _ in range(n)]
        return {k: np.stack([it[k] for it in items]) for k in KEYS}
