#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""History against single-frame: mean PSNR of method variants on held-out rendered sequences.

For each scene and sample count, every variant ``LABEL=SPEC`` runs ``afntool --denoise:SPEC`` over
the sequence (one filter, its history kept), and each base method also runs *single-frame*: every
frame denoised by its own afntool call (a fresh filter, no history); ``--no-motion`` specs run
without motion vectors and positions (afn's single-frame model). PSNR follows the evaluation's
convention (``afntool --compare``, docs/metrics.md). Prints a markdown table; ``--json`` keeps the
numbers. Used for docs/afn-evaluation.md's history-trust table::

    /usr/bin/python3 training/eval_history.py --data "$AFN_DATA/afn-v3/eval" \\
        --scenes atrium-1000000,room-1000000 --spp 1,16 \\
        --variants ta0=ta/antilag=0,ta=ta,afn=afn --single ta,afn
"""

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MEAN = re.compile(r"^mean\s+([0-9.eE+-]+|inf)\s")


def default_afntool():
    """The optimised build's afntool (build/), else any build folder's, else PATH's."""
    for pattern in ("build", "build*"):
        for path in sorted(glob.glob(os.path.join(HERE, "..", pattern, "cli", "afntool"))):
            return os.path.abspath(path)
    return "afntool"


def denoise_arg(spec):
    """``ta/antilag=0`` -> ``--denoise:method=ta:antilag=0``."""
    method, _, params = spec.partition("/")
    return "--denoise:method=" + method + (":" + params.replace("/", ":") if params else "")


def run(cmd):
    res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if res.returncode != 0:
        sys.exit("eval_history ERROR: %s failed:\n%s" % (" ".join(cmd), res.stdout[-2000:]))
    return res.stdout


def mean_psnr(text):
    for line in text.splitlines():
        m = MEAN.match(line.strip())
        if m:
            return float(m.group(1))
    sys.exit("eval_history ERROR: no mean line in afntool's output:\n" + text[-2000:])


def frames_of(folder):
    names = sorted(glob.glob(os.path.join(folder, "frame.[0-9][0-9][0-9][0-9].exr")))
    return [int(os.path.basename(n)[6:10]) for n in names]


NO_HISTORY = ["--aov", "motion=none", "--aov", "position=none"]


def score(args, folder, spec, single, tmp):
    frames = frames_of(folder)
    if not frames:
        sys.exit("eval_history ERROR: no frame.NNNN.exr in " + folder)
    rng = "%d-%d" % (frames[0], frames[-1])
    base = [args.afntool, "--threads", str(args.threads), "-q"]
    inp, ref = os.path.join(folder, "frame.####.exr"), os.path.join(folder, "reference.####.exr")
    if spec is None:  # the noisy input
        return mean_psnr(run(base[:-1] + ["--frames", rng, inp, "--compare", ref]))
    out = os.path.join(tmp, "out.####.exr")
    if single in (False, "nomotion"):
        extra = NO_HISTORY if single else []
        return mean_psnr(run(base[:-1] + extra + ["--frames", rng, inp, denoise_arg(spec), "-o",
                                                  out, "--compare", ref]))
    for f in frames:
        one = os.path.join(folder, "frame.%04d.exr" % f)
        run(base + [one, denoise_arg(spec), "-o", os.path.join(tmp, "out.%04d.exr" % f)])
    return mean_psnr(run(base[:-1] + ["--frames", rng, out, "--compare", ref]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", required=True, help="folder of the evaluation sequences")
    ap.add_argument("--scenes", required=True, help="comma list of sequence folders")
    ap.add_argument("--spp", default="1,16", help="sample counts (sppN/ folders)")
    ap.add_argument("--variants", required=True,
                    help="comma list LABEL=SPEC (SPEC: method/param=value/...)")
    ap.add_argument("--single", default="", help="comma list of specs also run single-frame")
    ap.add_argument("--no-motion", default="",
                    help="comma list of specs also run without motion and position (afn: its "
                    "single-frame model)")
    ap.add_argument("--afntool", default=default_afntool())
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    variants = [("input", None, False)]
    for item in args.variants.split(","):
        label, _, spec = item.partition("=")
        variants.append((label, spec or label, False))
    for spec in filter(None, args.single.split(",")):
        variants.append((spec + " single-frame", spec, True))
    for spec in filter(None, args.no_motion.split(",")):
        variants.append((spec + " without motion/position", spec, "nomotion"))
    results = {}
    for spp in args.spp.split(","):
        for scene in args.scenes.split(","):
            folder = os.path.join(args.data, scene, "spp" + spp)
            for label, spec, single in variants:
                with tempfile.TemporaryDirectory() as tmp:
                    v = score(args, folder, spec, single, tmp)
                results.setdefault(spp, {}).setdefault(label, {})[scene] = v
                print("%s spp %s %-28s %.3f" % (scene, spp, label, v), file=sys.stderr)
    scenes = args.scenes.split(",")
    for spp, table in results.items():
        print("\n%s spp, mean PSNR (dB) per sequence\n" % spp)
        print("| variant | " + " | ".join(scenes) + " | mean |")
        print("|---|" + "---:|" * (len(scenes) + 1))
        for label, row in table.items():
            vals = [row[s] for s in scenes]
            print("| %s | %s | %.2f |" % (label, " | ".join("%.2f" % v for v in vals),
                                           sum(vals) / len(vals)))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(results, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
