# SPDX-License-Identifier: Apache-2.0
"""Training data: rendered sequences (training/render-dataset, docs/dataset.md) turned into the AFN
inputs by the C++ library itself, so the Python and C++ inputs cannot drift:

    afntool --frames F SCENE/frame.####.exr --features:alphaMin=A CACHE/features.####.exr
    afntool --frames F SCENE/reference.####.exr -d float -o CACHE/target.####.exr

``--features`` runs the ``afn`` method's input preparation (the role mapping of any renderer's
files, the bad-input rule, the aux prefilter with the method's default ``aux=auto``, demodulation,
BMFR temporal accumulation, feature scaling) and writes what the network sees, one float layer per
feature (afnGetFilterTypeFeature):

    c1        irradiance      1-spp colour / max(d, 2^-10), linear HDR, >= 0
    cta       accumulated     TA-1spp: temporal accumulation of c1, linear HDR
    albedo    albedo          d, the demodulation factor: the albedo after the aux prefilter
                              (lib/core/stages/aux_prefilter.h; the file's albedo when it is clean),
                              [0, 1] (1 when the file has none); the remodulation multiplies by it
    normal01  normal01        prefiltered shading normal * 0.5 + 0.5, [0, 1]
    depth01   depth01         prefiltered per-frame min-max depth, [0, 1]
    history01 history01       1 / the frames the accumulated input holds, [1/255, 1] (1 where
                              it was reset; the history input of model.py)
    target    the reference's beauty (full radiance, albedo included), as afntool reads it

A scene folder holds frame.NNNN.exr and reference.NNNN.exr; a dataset root holds scene folders,
or is a generated dataset (``afn-dataset-2``, :mod:`afn.generated`) whose level folders
``<split>/<seq>/spp<S>`` are the scenes, chosen per sample count (:func:`find_scenes`).
Whole scenes are prepared once and kept in memory as float32 arrays; :class:`CropSampler` draws
128x128 crops with random flips and brightness jitter in [0.8, 1.2].
"""

import glob
import json
import os
import re
import tempfile

import numpy as np
import torch

from . import afntool, generated

FRAME_RE = re.compile(r"frame\.(\d+)\.exr$")
LAYOUT = ("a scene folder holds frame.NNNN.exr (the noisy render, any renderer's pass names that "
          "afntool maps) and reference.NNNN.exr (the converged beauty)")


class SceneError(ValueError):
    """A scene folder cannot be read as training data (the message says why and what it holds)."""
KEYS = ("c1", "cta", "albedo", "normal01", "depth01", "history01", "target")
# Dataset key -> (feature layer written by afntool --features, channel suffixes).
FEATURES = {"c1": ("irradiance", "RGB"), "cta": ("accumulated", "RGB"),
            "albedo": ("albedo", "RGB"), "normal01": ("normal01", "RGB"),
            "depth01": ("depth01", "Z"), "history01": ("history01", "Z")}


def read_layers(path, layers):
    """Read named channels of an EXR: {key: (H, W, C) float32} for {key: (layer, suffixes)}."""
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise OSError(f"cannot read {path}: {buf.geterror()}")
    spec = buf.spec()
    names = list(spec.channelnames)
    px = np.asarray(buf.get_pixels(oiio.FLOAT), np.float32).reshape(
        spec.height, spec.width, spec.nchannels)
    out = {}
    for key, (layer, suffixes) in layers.items():
        wanted = [f"{layer}.{c}" if layer else c for c in suffixes]
        missing = [n for n in wanted if n not in names]
        if missing:
            raise KeyError(f"{path}: no channel {', '.join(missing)} (has: {', '.join(names)})")
        out[key] = np.ascontiguousarray(px[..., [names.index(n) for n in wanted]])
    return out


def frame_numbers(scene_dir):
    """Sorted frame numbers (as text) that have both a noisy frame and a reference."""
    nums = []
    for f in glob.glob(os.path.join(scene_dir, "frame.*.exr")):
        m = FRAME_RE.search(f)
        if m and os.path.exists(os.path.join(scene_dir, f"reference.{m.group(1)}.exr")):
            nums.append(m.group(1))
    return sorted(nums)


def file_channels(path, tool=None):
    """Channel names of an image as the C++ reader sees them (``afntool --info --json``); [] when
    afntool cannot read it."""
    try:
        return json.loads(afntool.run(["--info", "--json", path], tool)).get("channels", [])
    except (afntool.AfntoolError, ValueError):
        return []


def _prepare(scene_dir, nums, args, path, tool):
    """Run afntool over a scene's frames; :class:`SceneError` with the file's channels on failure."""
    try:
        afntool.run(args, tool)
    except afntool.AfntoolError as e:
        first = os.path.join(scene_dir, f"{os.path.basename(path).split('.')[0]}.{nums[0]}.exr")
        chans = file_channels(first, tool)
        raise SceneError(
            f"{scene_dir}: afntool cannot prepare these frames ({e}). Channels of "
            f"{os.path.basename(first)}: {', '.join(chans) or '(unreadable)'}. Name the passes the "
            f"automatic role mapping misses with --aov ROLE=CHANNELS (roles: color albedo normal "
            f"depth position motion alpha), e.g. --aov color=diffuse.R,diffuse.G,diffuse.B") from e


def load_scene(scene_dir, alpha_min=0.2, max_frames=None, tool=None, aux="auto", aov=()):
    """Prepare every frame of one scene through afntool (in order: TA needs the history).

    Args:
        scene_dir: folder with frame.NNNN.exr and reference.NNNN.exr (any renderer's naming
            that afntool maps; frame numbers with 4 digits).
        alpha_min: temporal accumulation's minimum blend factor (the afn method's alphaMin).
        aux: the afn method's ``aux`` parameter (auto, clean, noisy; lib/core/stages/aux_prefilter.h):
            training data must be prepared as the filter will see it in use (default auto).
        max_frames: first frames only (None: all).
        tool: afntool path (None: :func:`afntool.find_afntool`).
        aov: ``ROLE=CHANNELS`` mappings passed to afntool as ``--aov`` (for passes the automatic
            role mapping of the C++ core does not find; the same option as afntool's).

    Raises:
        SceneError: no frames, or afntool cannot read them (names the file's channels).

    Returns:
        dict of numpy arrays, each (F, H, W, C) float32, keys :data:`KEYS`.
    """
    nums = frame_numbers(scene_dir)[:max_frames]
    if not nums:
        raise SceneError(f"{scene_dir}: no frame.NNNN.exr with a reference.NNNN.exr ({LAYOUT}); "
                         f"it holds: {', '.join(sorted(os.listdir(scene_dir))[:12]) or 'nothing'}")
    frames = afntool.frame_list(nums)
    tool = tool or afntool.require_afntool()  # a missing afntool is its own error
    overrides = [x for a in aov for x in ("--aov", a)]
    with tempfile.TemporaryDirectory(prefix="afn-features-") as cache:
        frame_path = os.path.join(scene_dir, "frame.####.exr")
        _prepare(scene_dir, nums, ["-q", "--frames", frames] + overrides
                 + [frame_path, f"--features:alphaMin={alpha_min}:aux={aux}",
                    os.path.join(cache, "features.####.exr")], frame_path, tool)
        ref_path = os.path.join(scene_dir, "reference.####.exr")
        _prepare(scene_dir, nums, ["-q", "--frames", frames] + overrides
                 + [ref_path, "-d", "float", "-o", os.path.join(cache, "target.####.exr")],
                 ref_path, tool)
        out = {k: [] for k in KEYS}
        for n in nums:
            n4 = f"{int(n):04d}"
            feats = read_layers(os.path.join(cache, f"features.{n4}.exr"), FEATURES)
            feats.update(read_layers(os.path.join(cache, f"target.{n4}.exr"),
                                     {"target": ("", "RGB")}))
            for k in KEYS:
                out[k].append(feats[k])
    return {k: np.stack(v).astype(np.float32) for k, v in out.items()}


def find_scenes(root, spp=None):
    """Scene folders under a dataset root (or the root itself if it is a scene).

    Args:
        root: a scene folder, a folder of scene folders, or a generated dataset.
        spp: sample counts to select (list of int or ``"1,16"``). A generated dataset needs them
            (its scenes are ``<family>-<seed>/spp<S>``); for other folders they must match the
            manifest's ``spp`` when it has one.

    Returns:
        {name: folder}, sorted by name.

    Raises:
        ValueError: ``spp`` missing for a generated dataset, or not a level of the dataset.
    """
    levels = generated.parse_levels(spp)
    m = generated.manifest(root)
    if m is not None:
        return generated.scenes(root, m, levels)[0]
    flat = os.path.join(root, "manifest.json")
    if levels and os.path.isfile(flat):
        with open(flat) as f:
            have = json.load(f).get("spp")
        if have is not None and levels != [int(have)]:
            raise ValueError(f"{root} holds {have}-spp inputs only, not {spp}")
    if frame_numbers(root):
        return {os.path.basename(os.path.normpath(root)): root}
    return {d: os.path.join(root, d) for d in sorted(os.listdir(root))
            if os.path.isdir(os.path.join(root, d)) and frame_numbers(os.path.join(root, d))}


def evaluation_scenes(root, spp=None):
    """Names of the scenes :func:`find_scenes` lists that must never be trained on (a generated
    dataset's ``eval`` split; empty for other folders)."""
    m = generated.manifest(root)
    if m is None:
        return set()
    return generated.scenes(root, m, generated.parse_levels(spp))[1]


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
        return self._crops(0)[0]

    def sample_pair(self):
        """(previous, current): the same crop window, flips and gain in two consecutive frames of
        one scene (for the temporal term of the loss; the window is fixed in the image, so camera
        and object motion show as they do in the output)."""
        return tuple(self._crops(1))

    def _crops(self, before):
        """Crops of frames f-before..f of one random scene, f >= before, with shared augmentation."""
        s = self.scenes[self.rng.randint(len(self.scenes))]
        frames = s["c1"].shape[0]
        f = self.rng.randint(min(before, frames - 1), frames)
        h, w = s["c1"].shape[1:3]
        y = self.rng.randint(max(h - self.crop, 0) + 1)
        x = self.rng.randint(max(w - self.crop, 0) + 1)
        outs = []
        for g in range(max(f - before, 0), f + 1):
            out = {}
            for k in KEYS:
                a = s[k][g, y:y + self.crop, x:x + self.crop]
                if a.shape[0] < self.crop or a.shape[1] < self.crop:
                    a = np.pad(a, ((0, self.crop - a.shape[0]), (0, self.crop - a.shape[1]), (0, 0)))
                out[k] = a
            outs.append(out)
        if len(outs) <= before:      # a one-frame scene: its frame is its own predecessor
            outs = [outs[0]] * (before + 1)
        flip_x, flip_y = self.rng.rand() < 0.5, self.rng.rand() < 0.5
        gain = np.float32(self.rng.uniform(0.8, 1.2))
        result = []
        for out in outs:
            if flip_x:
                out = {k: v[:, ::-1] for k, v in out.items()}
            if flip_y:
                out = {k: v[::-1] for k, v in out.items()}
            out = {k: (v * gain if k in ("c1", "cta", "target") else v) for k, v in out.items()}
            result.append({k: np.ascontiguousarray(v, np.float32) for k, v in out.items()})
        return result

    def batch(self, n):
        items = [self.sample() for _ in range(n)]
        return {k: np.stack([it[k] for it in items]) for k in KEYS}

    def pair_batch(self, n):
        """2n crops: the current frames of n pairs, then their previous frames (same order)."""
        pairs = [self.sample_pair() for _ in range(n)]
        items = [p[1] for p in pairs] + [p[0] for p in pairs]
        return {k: np.stack([it[k] for it in items]) for k in KEYS}
