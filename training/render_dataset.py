# SPDX-License-Identifier: Apache-2.0
"""Driver that renders the procedural scene library with Blender Cycles (see docs/dataset.md).

Runs with /usr/bin/python3 and calls ``blender -b`` once per scene (training/scenes/_runner.py does
the Blender side). Output layout::

    OUT/manifest.json                  settings, Blender version, per-scene records, render seconds
    OUT/<scene>/frame.NNNN.exr         1 spp, every pass afn maps (multilayer, view layer ViewLayer)
    OUT/<scene>/reference.NNNN.exr     Combined only, float32, --ref-spp samples
    OUT/<scene>/scene.json             the runner's record (parameters, cameras, per-file seconds)

Resumable: finished files are skipped, so rerunning the same command continues an interrupted run.
"""

import argparse
import ast
import json
import os
import subprocess
import sys
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES_DIR = os.path.join(HERE, "scenes")
RUNNER = os.path.join(SCENES_DIR, "_runner.py")

# Default dataset (docs/dataset.md explains the sizing for a 2-core machine, about 2 hours).
DEFAULT_FRAMES = 16
DEFAULT_HEIGHT = 180
DEFAULT_REF_SPP = 256
DEFAULT_SPP = 1
ASPECT = 16.0 / 9.0


class DatasetError(Exception):
    """A user-facing error of the driver (bad scene name, mismatched resume, Blender failure)."""


def scene_info(path):
    """Read DESCRIPTION, COVERS and DEFAULTS of a scene file without running Blender."""
    with open(path) as fh:
        tree = ast.parse(fh.read(), path)
    info = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1:
            name = getattr(node.targets[0], "id", None)
            if name in ("DESCRIPTION", "COVERS", "DEFAULTS"):
                info[name.lower()] = ast.literal_eval(node.value)
    for field in ("description", "covers", "defaults"):
        if field not in info:
            raise DatasetError("scene file lacks %s (%s)" % (field.upper(), path))
    return info


def list_scenes():
    """All scenes of the library: name -> info, sorted by name."""
    names = sorted(f[:-3] for f in os.listdir(SCENES_DIR)
                   if f.endswith(".py") and not f.startswith("_"))
    return {n: scene_info(os.path.join(SCENES_DIR, n + ".py")) for n in names}


def scene_seed(name, seed):
    """Per-scene seed: stable across runs and independent of which other scenes are rendered."""
    return seed * 10000 + zlib.crc32(name.encode()) % 10000


def width_for(height):
    """16:9 width for ``height`` pixels, rounded to an even number (72 -> 128, 180 -> 320)."""
    return int(round(height * ASPECT / 2.0)) * 2


def check_resume(scene_dir, expected):
    """Refuse to continue a scene directory rendered with other settings."""
    path = os.path.join(scene_dir, "scene.json")
    if not os.path.exists(path):
        return
    with open(path) as fh:
        old = json.load(fh)
    for key, value in expected.items():
        if key in old and old[key] != value:
            raise DatasetError("%s was rendered with %s=%r, not %r; use another --out (%s)"
                               % (scene_dir, key, old[key], value, path))


def render_scene(blender, name, scene_dir, settings, progress):
    """Render one scene with Blender; ``progress(line)`` gets each finished file. Returns scene.json."""
    cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", RUNNER, "--",
           "--scene", name, "--out", scene_dir, "--frames", str(settings["frames"]),
           "--width", str(settings["width"]), "--height", str(settings["height"]),
           "--spp", str(settings["spp"]), "--ref-spp", str(settings["ref_spp"]),
           "--seed", str(settings["seed"]),
           "--ref-seed-offset", str(settings["reference_seed_offset"])]
    os.makedirs(scene_dir, exist_ok=True)
    log_path = os.path.join(scene_dir, "blender.log")
    with open(log_path, "w") as log:
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        for line in proc.stdout:
            log.write(line)
            if line.startswith("afn: "):
                progress(line[5:].strip())
        rc = proc.wait()
    if rc != 0:
        raise DatasetError("Blender failed on scene %s with exit code %d; see %s"
                           % (name, rc, log_path))
    with open(os.path.join(scene_dir, "scene.json")) as fh:
        return json.load(fh)


def write_manifest(out, manifest):
    path = os.path.join(out, "manifest.json")
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(manifest, fh, indent=1)
    os.replace(tmp, path)


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="render-dataset", description=__doc__.split("\n")[0])
    ap.add_argument("--out", help="output directory")
    ap.add_argument("--scenes", default="", help="comma-separated scene names (default: all)")
    ap.add_argument("--frames", type=int, default=DEFAULT_FRAMES)
    ap.add_argument("--height", type=int, default=DEFAULT_HEIGHT, help="pixels; width is 16:9")
    ap.add_argument("--spp", type=int, default=DEFAULT_SPP, help="samples of the noisy frames")
    ap.add_argument("--ref-spp", type=int, default=DEFAULT_REF_SPP)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--ref-seed-offset", type=int, default=7919,
                    help="reference noise seed = scene seed + this (change it to get an "
                         "independent reference, e.g. for measuring reference noise)")
    ap.add_argument("--blender", default="blender", help="Blender executable")
    ap.add_argument("--list", action="store_true", help="list the scenes and exit")
    args = ap.parse_args(argv)
    if not args.list and not args.out:
        ap.error("--out is required (or use --list)")
    if args.frames < 1 or args.height < 8 or args.spp < 1 or args.ref_spp < 1:
        ap.error("--frames, --spp and --ref-spp must be >= 1 and --height >= 8")
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    scenes = list_scenes()
    if args.list:
        for name, info in scenes.items():
            print("%-16s %s\n%-16s covers: %s" % (name, info["description"], "",
                                                   ", ".join(info["covers"])))
        return 0
    chosen = [s for s in args.scenes.split(",") if s] or list(scenes)
    unknown = [s for s in chosen if s not in scenes]
    if unknown:
        raise DatasetError("unknown scene(s) %s; --list shows %s"
                           % (", ".join(unknown), ", ".join(scenes)))
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    manifest_path = os.path.join(out, "manifest.json")
    manifest = {}
    if os.path.exists(manifest_path):
        with open(manifest_path) as fh:
            manifest = json.load(fh)
    manifest.update({"format": "afn-dataset-1", "spp": args.spp, "ref_spp": args.ref_spp,
                     "frames": args.frames, "height": args.height, "width": width_for(args.height),
                     "seed": args.seed})
    records = manifest.setdefault("scenes", {})
    total_files = 2 * args.frames * len(chosen)
    done = [0]
    t_start = time.time()
    for i, name in enumerate(chosen):
        settings = {"frames": args.frames, "width": width_for(args.height), "height": args.height,
                    "spp": args.spp, "ref_spp": args.ref_spp, "seed": scene_seed(name, args.seed),
                    "reference_seed_offset": args.ref_seed_offset}
        scene_dir = os.path.join(out, name)
        check_resume(scene_dir, settings)

        def progress(line, i=i, name=name):
            done[0] += 1
            print("[%d/%d %s] %s (%d/%d files, %.0f s)" % (i + 1, len(chosen), name, line, done[0],
                                                        total_files, time.time() - t_start),
                  flush=True)

        t0 = time.time()
        state = render_scene(args.blender, name, scene_dir, settings, progress)
        record = {k: state.get(k) for k in ("description", "covers", "params", "seed", "frames",
                                            "width", "height", "spp", "ref_spp",
                                            "reference_seed_offset", "blender", "view_layer")}
        seconds = state.get("seconds", {})
        cpu = state.get("cpu_seconds", {})
        record.update({
            "dir": name,
            "render_seconds": round(sum(seconds.values()), 2),
            "noisy_seconds": round(sum(v for k, v in seconds.items() if k.startswith("frame")), 2),
            "reference_seconds": round(sum(v for k, v in seconds.items()
                                           if k.startswith("reference")), 2),
            "cpu_seconds": round(sum(cpu.values()), 2),
            "wall_seconds_last_run": round(time.time() - t0, 2),
        })
        records[name] = record
        manifest["blender"] = state.get("blender")
        manifest["render_seconds"] = round(sum(r["render_seconds"] for r in records.values()), 2)
        manifest["cpu_seconds"] = round(sum(r.get("cpu_seconds", 0) for r in records.values()), 2)
        write_manifest(out, manifest)
    print("render-dataset: %d scene(s) in %s, %.0f s this run" % (len(chosen), out,
                                                                   time.time() - t_start))
    return 0


def cli():
    try:
        sys.exit(main())
    except DatasetError as err:
        sys.exit("render-dataset ERROR: %s" % err)
    except KeyboardInterrupt:
        sys.exit("render-dataset: interrupted; rerun the same command to resume")
