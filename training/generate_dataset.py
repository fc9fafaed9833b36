# SPDX-License-Identifier: Apache-2.0
"""Driver that renders the generated training and evaluation sequences (see docs/dataset.md).

Runs with /usr/bin/python3; for every (family, seed) of the plan it writes the scene description
(training/scenes/generator), runs ``nice blender -b -t THREADS`` on
training/scenes/_generated_runner.py and post-processes the result (dataset_exr.py). Output layout::

    OUT/manifest.json                          settings, split, one record per sequence, seconds
    OUT/<split>/<family>-<seed>/description.json   the generator's scene description
    OUT/<split>/<family>-<seed>/scene.json         the runner's record (exposure, cameras, seconds)
    OUT/<split>/<family>-<seed>/spp<S>/frame.NNNN.exr   S samples, every pass afn maps
    OUT/<split>/<family>-<seed>/spp<S>/reference.NNNN.exr   what frame.NNNN.exr is scored against
    OUT/train/<family>-<seed>/extra.NNNN.exr           an extra independent render (--extra-spp)
    OUT/eval/<family>-<seed>/reference.NNNN.exr        clean reference (--eval-ref-spp), the mean
    OUT/eval/<family>-<seed>/reference_partK.NNNN.exr  of these independent parts

``<split>`` is ``train`` or ``eval`` (generator/split.py). A training level's reference is the
sample-weighted mean of the *other* levels and ``extra`` (independent of that level's input: with
the defaults 100, 97, 85 and 37 samples for levels 1, 4, 16 and 64); an evaluation level's
reference is a symlink to the clean ``../reference.NNNN.exr``. Resumable: rerun the same command and
finished sequences and files are skipped; a sequence directory made with other settings, or whose
description the generator no longer reproduces, is refused with a message.
"""

import argparse
import json
import os
import subprocess
import sys
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "scenes"))
import dataset_exr  # noqa: E402
from generator import split  # noqa: E402
from generator.describe import describe  # noqa: E402
from render_dataset import DatasetError, check_resume, width_for, write_manifest  # noqa: E402

RUNNER = os.path.join(HERE, "scenes", "_generated_runner.py")
FORMAT = "afn-dataset-2"
VECTOR_NOTE = ("Vector of an unblurred 1-spp render of the same frame (vector.NNNN.exr): Cycles "
               "writes an all-zero Vector pass when motion blur is on")

# Defaults: the budgeted dataset of docs/dataset.md (2.1 h of two idle cores; ~9 h niced, shared).
DEFAULTS = {"frames": 6, "height": 144, "train": 196, "levels": "1,4,16,64", "extra_spp": 16,
            "eval_frames": 8, "eval_held_out": 3, "eval_reserved": 3, "eval_levels": "1,16",
            "eval_ref_spp": 512, "eval_ref_parts": 2}


def noise_seed(name):
    """Base Cycles noise seed of a sequence: distinct per sequence, stable across runs."""
    return (zlib.crc32(name.encode()) % 100000) * 1000


def plan(args):
    """[(split, family, seed, frames, levels, reference spp, parts, reference name)].

    Training sequences come first (``--order train-first``, the default): they are cheap (no clean
    reference) and usable as soon as each finishes, while an evaluation sequence spends most of its
    time on its clean reference parts. ``--order eval-first`` renders the evaluation set first.
    """
    if args.sequences:
        pairs = []
        for item in args.sequences.split(","):
            family, _, seed = item.partition(":")
            if family not in split.FAMILIES or not seed.isdigit():
                raise DatasetError("--sequences wants FAMILY:SEED items (families: %s), not %r"
                                   % (", ".join(split.FAMILIES), item))
            pairs.append((family, int(seed)))
        evals = [p for p in pairs if split.is_evaluation(*p)]
        trains = [p for p in pairs if split.is_training(*p)]
    else:
        evals = split.evaluation_sequences(args.eval_held_out, args.eval_reserved)
        trains = split.training_sequences(args.train)
    ev = [("eval", f, s, args.eval_frames, args.eval_levels, args.eval_ref_spp,
           args.eval_ref_parts, "reference") for f, s in evals]
    tr = [("train", f, s, args.frames, args.levels, args.extra_spp, 1, "extra") for f, s in trains]
    out = ev + tr if args.order == "eval-first" else tr + ev
    if args.only:
        out = [p for p in out if p[0] == args.only]
    return out


def write_description(seq_dir, desc):
    """Write description.json, or check that an existing one is exactly what the generator makes."""
    path = os.path.join(seq_dir, "description.json")
    if os.path.exists(path):
        with open(path) as fh:
            if json.load(fh) != json.loads(json.dumps(desc)):
                raise DatasetError("%s differs from what the generator now makes for this "
                                   "(family, seed); use another --out" % path)
        return path
    os.makedirs(seq_dir, exist_ok=True)
    with open(path + ".tmp", "w") as fh:
        json.dump(desc, fh, indent=1)
    os.replace(path + ".tmp", path)
    return path


def run_blender(args, desc_path, seq_dir, settings, progress):
    """Render one sequence with Blender (niced, fixed thread count); return its scene.json."""
    cmd = ["nice", "-n", str(args.nice), args.blender, "-b", "--factory-startup",
           "-t", str(args.threads), "--python-exit-code", "1", "--python", RUNNER, "--",
           "--description", desc_path, "--out", seq_dir, "--width", str(settings["width"]),
           "--height", str(settings["height"]), "--levels", settings["levels"],
           "--reference-spp", str(settings["reference_spp"]),
           "--reference-parts", str(settings["reference_parts"]),
           "--reference-name", settings["reference_name"],
           "--seed", str(settings["noise_seed"]), "--threads", str(args.threads)]
    log_path = os.path.join(seq_dir, "blender.log")
    with open(log_path, "w") as log:
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        for line in proc.stdout:
            log.write(line)
            if line.startswith("afn: wrote"):
                progress(line[5:].strip())
        rc = proc.wait()
    if rc != 0:
        raise DatasetError("Blender failed on %s (exit code %d); see %s" % (seq_dir, rc, log_path))
    with open(os.path.join(seq_dir, "scene.json")) as fh:
        return json.load(fh)


def level_targets(levels, extra_spp):
    """Samples of each training level's target: the other levels plus the extra render."""
    return {spp: sum(levels) - spp + extra_spp for spp in levels}


def post_process(seq_dir, frames, settings, blur):
    """Splice unblurred vectors, check sample headers, and give every level its references.

    Evaluation: average the reference parts, link ``spp<S>/reference.NNNN.exr`` to the result.
    Training: write each level's target, the sample-weighted mean of the other levels and
    ``extra.NNNN.exr``.
    """
    levels = [int(x) for x in settings["levels"].split(",")]
    parts = settings["reference_parts"]
    for f in range(frames):
        ref = os.path.join(seq_dir, "reference.%04d.exr" % f)
        if settings["reference_name"] == "reference" and parts > 1 and not os.path.exists(ref):
            dataset_exr.average_parts([os.path.join(seq_dir, "reference_part%d.%04d.exr" % (k, f))
                                       for k in range(parts)], ref)
        for spp in levels:
            frame = os.path.join(seq_dir, "spp%d" % spp, "frame.%04d.exr" % f)
            if blur:
                dataset_exr.splice_vector(frame, os.path.join(seq_dir, "vector.%04d.exr" % f),
                                          VECTOR_NOTE)
            if dataset_exr.samples(frame) != spp:
                raise DatasetError("%s: header says %s samples, expected %d"
                                   % (frame, dataset_exr.samples(frame), spp))
            target = os.path.join(seq_dir, "spp%d" % spp, "reference.%04d.exr" % f)
            if os.path.lexists(target):
                continue
            if settings["reference_name"] == "reference":
                os.symlink(os.path.join("..", "reference.%04d.exr" % f), target)
                continue
            others = [os.path.join(seq_dir, "spp%d" % o, "frame.%04d.exr" % f)
                      for o in levels if o != spp]
            others.append(os.path.join(seq_dir, "extra.%04d.exr" % f))
            dataset_exr.sample_weighted_mean(
                others, target, "sample-weighted mean of %s: independent of spp%d's noise"
                % (", ".join(os.path.relpath(p, seq_dir) for p in others), spp))


def record(split_name, desc, state, settings, seq_dir, out):
    """Manifest record of one finished sequence."""
    secs, cpu = state.get("seconds", {}), state.get("cpu_seconds", {})

    def total(table, prefix):
        return round(sum(v for k, v in table.items() if k.startswith(prefix)), 2)

    series = ["spp%d/" % int(s) for s in settings["levels"].split(",")] + [
        settings["reference_name"], "vector", "probe"]
    return {"split": split_name, "family": desc["family"], "seed": desc["seed"],
            "dir": os.path.relpath(seq_dir, out), "summary": desc["summary"],
            "levels": [int(s) for s in settings["levels"].split(",")], "frames": desc["frames"],
            "reference_samples": (
                {"spp%s" % s: settings["reference_spp"] for s in settings["levels"].split(",")}
                if split_name == "eval" else
                {"spp%d" % s: n for s, n in level_targets(
                    [int(x) for x in settings["levels"].split(",")],
                    settings["reference_spp"]).items()}),
            "reference_spp": settings["reference_spp"],
            "reference_parts": settings["reference_parts"], "noise_seed": settings["noise_seed"],
            "exposure": state.get("exposure"), "motion_blur": desc["motion_blur"],
            "vector_source": VECTOR_NOTE if desc["motion_blur"] else "Blender's Vector pass",
            "seconds": {k.rstrip("/"): total(secs, k) for k in series},
            "cpu_seconds": {k.rstrip("/"): total(cpu, k) for k in series},
            "render_seconds": round(sum(secs.values()), 2),
            "render_cpu_seconds": round(sum(cpu.values()), 2), "complete": True}


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="generate-dataset", description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True,
                    help="output directory, e.g. $AFN_DATA/afn-v2 (docs/dataset.md)")
    d = DEFAULTS
    ap.add_argument("--frames", type=int, default=d["frames"], help="frames per training sequence")
    ap.add_argument("--eval-frames", type=int, default=d["eval_frames"])
    ap.add_argument("--height", type=int, default=d["height"], help="pixels; width is 16:9")
    ap.add_argument("--train", type=int, default=d["train"], help="training sequences")
    ap.add_argument("--levels", default=d["levels"], help="training input sample counts")
    ap.add_argument("--extra-spp", type=int, default=d["extra_spp"],
                    help="samples of the extra independent render in every training target")
    ap.add_argument("--eval-held-out", type=int, default=d["eval_held_out"],
                    help="evaluation scenes of the held-out family")
    ap.add_argument("--eval-reserved", type=int, default=d["eval_reserved"],
                    help="evaluation scenes from reserved seeds of training families")
    ap.add_argument("--eval-levels", default=d["eval_levels"])
    ap.add_argument("--eval-ref-spp", type=int, default=d["eval_ref_spp"])
    ap.add_argument("--eval-ref-parts", type=int, default=d["eval_ref_parts"],
                    help="independent parts the evaluation reference is averaged from")
    ap.add_argument("--only", choices=("train", "eval"), help="render only one split")
    ap.add_argument("--order", choices=("train-first", "eval-first"), default="train-first",
                    help="which split renders first (default: training, usable early)")
    ap.add_argument("--sequences", default="",
                    help="render these FAMILY:SEED pairs instead of the plan (split by split.py)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--nice", type=int, default=19)
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--plan", action="store_true", help="print the sequences and exit")
    return ap.parse_args(argv)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    todo = plan(args)
    if args.plan:
        for split_name, family, seed, frames, levels, ref_spp, parts, ref_name in todo:
            print("%-5s %-24s %d frames, levels %-10s %s %d spp (%d part(s))"
                  % (split_name, split.sequence_name(family, seed), frames, levels, ref_name,
                     ref_spp, parts))
        return 0
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    manifest_path = os.path.join(out, "manifest.json")
    manifest = json.load(open(manifest_path)) if os.path.exists(manifest_path) else {}
    manifest.update({"format": FORMAT, "frames": args.frames, "eval_frames": args.eval_frames,
                     "height": args.height, "levels": args.levels, "extra_spp": args.extra_spp,
                     "eval_levels": args.eval_levels, "eval_ref_spp": args.eval_ref_spp,
                     "eval_ref_parts": args.eval_ref_parts,
                     "width": width_for(args.height),
                     "split": {"held_out_families": list(split.HELD_OUT_FAMILIES),
                               "train_families": list(split.TRAIN_FAMILIES),
                               "eval_seed_start": split.EVAL_SEED_START},
                     "threads": args.threads, "nice": args.nice})
    records = manifest.setdefault("sequences", {})
    t_start, done = time.time(), [0]
    for i, (split_name, family, seed, frames, levels, ref_spp, parts, ref_name) in \
            enumerate(todo):
        name = split.sequence_name(family, seed)
        seq_dir = os.path.join(out, split_name, name)
        if records.get(name, {}).get("complete") and os.path.exists(seq_dir):
            continue
        desc = describe(family, seed, frames)
        settings = {"width": width_for(args.height), "height": args.height, "levels": levels,
                    "reference_spp": ref_spp, "reference_parts": parts,
                    "reference_name": ref_name, "noise_seed": noise_seed(name)}
        check_resume(seq_dir, {k: v for k, v in settings.items() if k != "noise_seed"})
        desc_path = write_description(seq_dir, desc)

        def progress(line, i=i, name=name):
            done[0] += 1
            print("[%d/%d %s] %s (%d files, %.0f s)" % (i + 1, len(todo), name, line, done[0],
                                                       time.time() - t_start), flush=True)

        state = run_blender(args, desc_path, seq_dir, settings, progress)
        post_process(seq_dir, frames, settings, desc["motion_blur"] is not None)
        records[name] = record(split_name, desc, state, settings, seq_dir, out)
        manifest["blender"] = state.get("blender")
        manifest["render_seconds"] = round(sum(r["render_seconds"] for r in records.values()), 2)
        manifest["render_cpu_seconds"] = round(sum(r["render_cpu_seconds"]
                                                   for r in records.values()), 2)
        write_manifest(out, manifest)
        print("generate-dataset: finished %s (%d/%d, %.0f s)" % (name, i + 1, len(todo),
                                                                 time.time() - t_start), flush=True)
    print("generate-dataset: %d sequence(s) in %s, %.0f s this run"
          % (len(todo), out, time.time() - t_start))
    return 0


def cli():
    try:
        sys.exit(main())
    except DatasetError as err:
        sys.exit("generate-dataset ERROR: %s" % err)
    except KeyboardInterrupt:
        sys.exit("generate-dataset: interrupted; rerun the same command to resume")
