# SPDX-License-Identifier: Apache-2.0
"""Render one procedural training scene (run by Blender; called by training/render-dataset).

Usage: blender -b --factory-startup --python training/scenes/_runner.py -- --scene NAME --out DIR
           [--frames 16] [--width 320] [--height 180] [--spp 1] [--ref-spp 256] [--seed 0]
           [--ref-seed-offset 7919] [--params JSON]

Writes DIR/frame.NNNN.exr (``--spp`` samples, all passes), DIR/reference.NNNN.exr (Combined,
float, ``--ref-spp`` samples, another noise seed) for frames 0..N-1 and DIR/scene.json (parameters,
seeds, sample counts, Blender version, per-file render wall and CPU seconds, per-frame camera). Files that
exist are skipped (resumable); each file is written under a temporary name and then renamed, so an
interrupted render never leaves a file that looks finished.
"""

import argparse
import importlib
import json
import os
import random
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "examples", "blender"))
import afn_render  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="_runner.py")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--frames", type=int, default=16)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--spp", type=int, default=1)
    ap.add_argument("--ref-spp", type=int, default=256)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--ref-seed-offset", type=int, default=afn_render.REFERENCE_SEED_OFFSET,
                    help="reference noise seed = seed + this")
    ap.add_argument("--params", default="{}", help="JSON object overriding the scene's DEFAULTS")
    return ap.parse_args(argv)


def camera_record(scene):
    """Camera of the current frame: world matrix (row-major 4x4), lens and sensor (mm)."""
    cam = scene.camera
    return {
        "matrix_world": [list(row) for row in cam.matrix_world],
        "lens_mm": cam.data.lens,
        "sensor_width_mm": cam.data.sensor_width,
        "sensor_fit": cam.data.sensor_fit,
    }


def load_state(path):
    if os.path.exists(path):
        with open(path) as fh:
            return json.load(fh)
    return {}


def render_frames(scene, out, stem, frames, spp, state, state_path):
    """Render frames 0..frames-1 of the configured scene to OUT/STEM.NNNN.exr, skipping finished
    ones; each written to a .partial file and renamed (a killed render leaves no half frame).
    Wall and CPU seconds per file go into state["seconds"] / state["cpu_seconds"] (saved after
    every frame, so a resumed render keeps them)."""
    times = state.setdefault("seconds", {})
    cpu_times = state.setdefault("cpu_seconds", {})
    for f in range(frames):
        final = os.path.join(out, "%s.%04d.exr" % (stem, f))
        if os.path.exists(final):
            print("afn: skip %s" % final, flush=True)
            continue
        partial = os.path.join(out, "%s.%04d.partial.exr" % (stem, f))
        cpu0 = time.process_time()
        secs = afn_render.render_frame(scene, f, partial)
        os.replace(partial, final)
        name = os.path.relpath(final, out)
        times[name] = round(secs, 2)
        # CPU seconds of all Blender threads: a load-independent measure for estimates.
        cpu_times[name] = round(time.process_time() - cpu0, 2)
        save_state(state_path, state)
        print("afn: wrote %s (%d spp, %.1f s)" % (name, spp, secs), flush=True)


def save_state(path, state):
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(state, fh, indent=1)
    os.replace(tmp, path)


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    module = importlib.import_module(args.scene)
    params = dict(module.DEFAULTS)
    params.update(json.loads(args.params))
    rng = random.Random(args.seed)
    scene_params = module.build(params, rng, 0, args.frames - 1)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 0, args.frames - 1

    state_path = os.path.join(out, "scene.json")
    state = load_state(state_path)
    state.update({
        "scene": args.scene, "description": module.DESCRIPTION, "covers": module.COVERS,
        "params": scene_params, "seed": args.seed, "frames": args.frames,
        "width": args.width, "height": args.height, "spp": args.spp, "ref_spp": args.ref_spp,
        "reference_seed_offset": args.ref_seed_offset,
        "blender": bpy.app.version_string, "view_layer": afn_render.VIEW_LAYER_NAME,
    })
    cameras = state.setdefault("cameras", {})
    for f in range(args.frames):
        scene.frame_set(f)
        cameras[str(f)] = camera_record(scene)
    save_state(state_path, state)

    for kind, name, spp in (("noisy", "frame", args.spp), ("reference", "reference", args.ref_spp)):
        afn_render.setup(scene, kind, args.width, args.height, spp, args.seed, args.ref_seed_offset)
        render_frames(scene, out, name, args.frames, spp, state, state_path)


if __name__ == "__main__":
    main()
