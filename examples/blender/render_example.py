# SPDX-License-Identifier: Apache-2.0
"""Render the example sequence with Cycles (run by Blender, see scripts/render-example.sh).

Usage: blender -b --factory-startup --python examples/blender/render_example.py -- \
           --out DIR [--frames 8] [--first 0] [--width 320] [--height 180] [--spp 1] \
           [--ref-spp 1024] [--seed 1] [--kinds noisy,reference] [--noisy-name frame] \
           [--ref-name reference] [--only-frames 0,3] [--skip-existing] [--light-passes]

Writes DIR/<noisy-name>.NNNN.exr (all passes, ``--spp`` samples) and DIR/<ref-name>.NNNN.exr
(Combined only, float, ``--ref-spp`` samples) and appends per-frame timings to DIR/render-times.json.
"""

import argparse
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import afn_render  # noqa: E402
import example_scene  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="render_example.py")
    ap.add_argument("--out", required=True)
    ap.add_argument("--frames", type=int, default=8)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--spp", type=int, default=1)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--kinds", default="noisy,reference")
    ap.add_argument("--noisy-name", default="frame")
    ap.add_argument("--ref-name", default="reference")
    ap.add_argument("--only-frames", default="", help="comma-separated subset of frames")
    ap.add_argument("--skip-existing", action="store_true")
    ap.add_argument("--light-passes", action="store_true",
                    help="also write the light-path passes (DiffDir, ..., Emit, Env) in both kinds")
    return ap.parse_args(argv)


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    scene, params = example_scene.build({"frames": args.frames}, args.seed, args.first)
    frames = range(args.first, args.first + args.frames)
    if args.only_frames:
        frames = [int(f) for f in args.only_frames.split(",")]
    log_path = os.path.join(out, "render-times.json")
    log = json.load(open(log_path)) if os.path.exists(log_path) else []
    for kind in args.kinds.split(","):
        spp = args.spp if kind == "noisy" else args.ref_spp
        name = args.noisy_name if kind == "noisy" else args.ref_name
        afn_render.setup(scene, kind, args.width, args.height, spp, args.seed,
                         light_passes=args.light_passes)
        for f in frames:
            path = os.path.join(out, "%s.%04d.exr" % (name, f))
            if args.skip_existing and os.path.exists(path):
                print("afn: skip existing %s" % path, flush=True)
                continue
            secs = afn_render.render_frame(scene, f, path)
            print("afn: wrote %s (%d spp, %.1f s)" % (path, spp, secs), flush=True)
            log.append({"file": os.path.basename(path), "kind": kind, "frame": f, "spp": spp,
                        "width": args.width, "height": args.height, "seed": args.seed,
                        "seconds": round(secs, 2), "blender": bpy.app.version_string})
            with open(log_path, "w") as fh:
                json.dump(log, fh, indent=1)


if __name__ == "__main__":
    main()
