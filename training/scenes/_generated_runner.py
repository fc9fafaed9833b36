# SPDX-License-Identifier: Apache-2.0
"""Render one generated scene (run by Blender; called by training/generate-dataset).

Usage: blender -b --factory-startup --python training/scenes/_generated_runner.py -- \\
           --description DIR/description.json --out DIR [--width 256] [--height 144] \\
           [--levels 1,4,16,64] [--reference-spp 16] [--reference-parts 1] [--reference-name extra] \
           [--seed 0] [--threads 2]

Builds the description (generator/blender_build.py), sets the film exposure so frame 0's
log-average luminance (over pixels that are not black) matches the description's key, with the
95th percentile kept at most 8 (a 16-spp probe at quarter size), then writes
for frames 0..N-1:

* ``spp<S>/frame.NNNN.exr`` for every level S: S samples, every pass afn maps (noise seed
  ``seed + 1 + level index``);
* ``<name>.NNNN.exr`` (``--reference-name``, default ``reference``; Combined, float32,
  ``--reference-spp`` samples, seed ``seed + 100``), or with ``--reference-parts K`` the K
  independent parts ``<name>_partK.NNNN.exr`` of ``--reference-spp / K`` samples each (seeds
  ``seed + 100 + k``); the driver averages parts into evaluation references and combines a
  training sequence's ``extra`` render with its levels into per-level targets;
* with motion blur on: ``vector.NNNN.exr``, a 1-spp render of every pass with motion blur off,
  because Cycles writes an all-zero Vector pass when motion blur is on (the driver copies its Vector
  channels into the blurred frames);
* ``scene.json``: settings, seeds, exposure, per-file wall and CPU seconds, per-frame cameras.

Files that exist are skipped; each is written under a temporary name and renamed when complete.
"""

import argparse
import json
import math
import os
import sys
import tempfile
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "examples", "blender"))
import afn_render  # noqa: E402
from _runner import camera_record, load_state, render_frames, save_state  # noqa: E402
from generator import blender_build  # noqa: E402

PROBE_SPP = 16
EXPOSURE_LIMIT = 2.0 ** 8  # film exposure stays within 8 stops of 1
HIGHLIGHT_LIMIT = 8.0  # largest 95th-percentile luminance after exposure


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="_generated_runner.py")
    ap.add_argument("--description", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--height", type=int, default=144)
    ap.add_argument("--levels", default="1,4,16,64")
    ap.add_argument("--reference-spp", type=int, default=16)
    ap.add_argument("--reference-parts", type=int, default=1)
    ap.add_argument("--reference-name", default="reference")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=2)
    return ap.parse_args(argv)


def jobs(args, blur):
    """(file stem, kind, samples, noise seed, motion blur) of every file series to render."""
    levels = [int(x) for x in args.levels.split(",") if x]
    out = [("spp%d/frame" % spp, "noisy", spp, args.seed + 1 + i, blur)
           for i, spp in enumerate(levels)]
    parts = max(1, args.reference_parts)
    if parts == 1:
        out.append((args.reference_name, "reference", args.reference_spp, args.seed + 100, blur))
    else:
        for k in range(parts):
            out.append(("%s_part%d" % (args.reference_name, k), "reference",
                        args.reference_spp // parts, args.seed + 100 + k, blur))
    if blur:
        out.append(("vector", "noisy", 1, args.seed + 200, False))
    return out


def configure(scene, desc, kind, width, height, spp, seed, blur, threads, exposure):
    """Render settings of one file series on top of the shared afn settings."""
    afn_render.setup(scene, kind, width, height, spp, seed, ref_seed_offset=0)
    blender_build.render_settings(scene, desc)
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.cycles.film_exposure = exposure
    scene.render.use_motion_blur = bool(blur)
    if blur:
        scene.render.motion_blur_shutter = desc["motion_blur"]["shutter"]


def probe_exposure(scene, desc, args):
    """Film exposure that brings frame 0's log-average luminance to ``desc['exposure']['key']``."""
    configure(scene, desc, "reference", max(16, args.width // 4), max(9, args.height // 4),
              PROBE_SPP, args.seed + 300, False, args.threads, 1.0)
    scene.render.image_settings.file_format = "OPEN_EXR"
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "probe.exr")
        afn_render.render_frame(scene, 0, path)
        img = bpy.data.images.load(path)
        px = np.array(img.pixels[:], dtype=np.float64).reshape(-1, 4)
        bpy.data.images.remove(img)
    lum = np.maximum(np.nan_to_num(px[:, 0] * 0.2126 + px[:, 1] * 0.7152 + px[:, 2] * 0.0722), 0)
    lit = lum[lum > 1e-6]  # a black sky or void would drag a log-average to zero
    if lit.size < 0.02 * lum.size:
        lit = np.array([desc["exposure"]["key"]])
    log_average = float(math.exp(np.mean(np.log(lit))))
    exposure = desc["exposure"]["key"] / log_average
    # Keep the brightest 5 % of the frame from being pushed far beyond white.
    exposure = min(exposure, HIGHLIGHT_LIMIT / max(1e-9, float(np.percentile(lum, 95))))
    exposure = min(EXPOSURE_LIMIT, max(1.0 / EXPOSURE_LIMIT, exposure))
    return {"key": desc["exposure"]["key"], "probe_log_average": round(log_average, 6),
            "film_exposure": round(exposure, 6), "probe_spp": PROBE_SPP}


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    with open(args.description) as fh:
        desc = json.load(fh)
    scene = blender_build.build(desc)
    blur = desc["motion_blur"] is not None
    state_path = os.path.join(out, "scene.json")
    state = load_state(state_path)
    state.update({"family": desc["family"], "seed": desc["seed"], "frames": desc["frames"],
                  "width": args.width, "height": args.height, "levels": args.levels,
                  "reference_spp": args.reference_spp, "reference_parts": args.reference_parts,
                  "reference_name": args.reference_name,
                  "world_map_resolution": blender_build.world_map_resolution(desc["world"]),
                  "noise_seed": args.seed, "motion_blur": blur, "blender": bpy.app.version_string,
                  "view_layer": afn_render.VIEW_LAYER_NAME})
    times = state.setdefault("seconds", {})
    cpu_times = state.setdefault("cpu_seconds", {})
    cameras = state.setdefault("cameras", {})
    for f in range(desc["frames"]):
        scene.frame_set(f)
        cameras[str(f)] = camera_record(scene)
    if "exposure" not in state:
        cpu0, t0 = time.process_time(), time.time()
        state["exposure"] = probe_exposure(scene, desc, args)
        times["probe"], cpu_times["probe"] = round(time.time() - t0, 2), \
            round(time.process_time() - cpu0, 2)
    save_state(state_path, state)
    exposure = state["exposure"]["film_exposure"]

    for stem, kind, spp, seed, use_blur in jobs(args, blur):
        configure(scene, desc, kind, args.width, args.height, spp, seed, use_blur, args.threads,
                  exposure)
        os.makedirs(os.path.dirname(os.path.join(out, stem)), exist_ok=True)
        render_frames(scene, out, stem, desc["frames"], spp, state, state_path)


if __name__ == "__main__":
    main()
