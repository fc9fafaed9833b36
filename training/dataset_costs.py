#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Render cost of a ``generate-dataset`` output, per file series and per family, and a projection.

Usage: /usr/bin/python3 training/dataset_costs.py DATASET [--plan-train N] [--json OUT.json]

Reads every finished sequence's scene.json (per-file wall and CPU seconds, the CPU seconds summing
all Blender threads) and prints, per split and series (``spp1``, ``spp4``, ..., ``extra``,
``reference_part0``, ``vector``, ``probe``), the mean CPU and wall seconds per frame, their ratio
(how many cores the render got on average), per-family CPU seconds per sequence, and the time the
whole plan (6 evaluation sequences and N training sequences) takes at the measured rates.
"""

import argparse
import collections
import json
import os
import re
import sys

SERIES_RE = re.compile(r"^(?:(spp\d+)/frame|([a-z_0-9]+?))\.\d{4}\.exr$")


def series_of(name):
    """File series of a scene.json key: 'spp4/frame.0003.exr' -> 'spp4', 'probe' -> 'probe'."""
    m = SERIES_RE.match(name)
    return (m.group(1) or m.group(2)) if m else name


def collect(root):
    """{split: {series: [cpu, wall, files]}}, {split: {family: [cpu per sequence]}}, seq counts."""
    manifest = json.load(open(os.path.join(root, "manifest.json")))
    per_series = collections.defaultdict(lambda: collections.defaultdict(lambda: [0.0, 0.0, 0]))
    per_family = collections.defaultdict(lambda: collections.defaultdict(list))
    for name, rec in manifest.get("sequences", {}).items():
        state = json.load(open(os.path.join(root, rec["dir"], "scene.json")))
        total = 0.0
        for key, cpu in state.get("cpu_seconds", {}).items():
            acc = per_series[rec["split"]][series_of(key)]
            acc[0] += cpu
            acc[1] += state["seconds"].get(key, 0.0)
            acc[2] += 1
            total += cpu
        per_family[rec["split"]][rec["family"]].append(total)
    return per_series, per_family, manifest


def main(argv):
    ap = argparse.ArgumentParser(prog="dataset_costs.py")
    ap.add_argument("dataset")
    ap.add_argument("--plan-train", type=int, default=196)
    ap.add_argument("--plan-eval", type=int, default=6)
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    per_series, per_family, manifest = collect(args.dataset)
    report = {"series": {}, "families": {}, "sequence_cpu_seconds": {}}
    for split_name in sorted(per_series):
        print("%s: per file (frame)            CPU s    wall s   cores used" % split_name)
        for series, (cpu, wall, n) in sorted(per_series[split_name].items()):
            print("  %-26s %8.2f %9.2f %8.2f" % (series, cpu / n, wall / n, cpu / max(wall, 1e-9)))
            report["series"]["%s/%s" % (split_name, series)] = {
                "cpu_s": round(cpu / n, 3), "wall_s": round(wall / n, 3), "files": n}
        seqs = [c for fam in per_family[split_name].values() for c in fam]
        mean = sum(seqs) / len(seqs)
        report["sequence_cpu_seconds"][split_name] = round(mean, 1)
        print("  %d sequences, mean %.0f CPU s per sequence" % (len(seqs), mean))
        for fam, vals in sorted(per_family[split_name].items()):
            report["families"]["%s/%s" % (split_name, fam)] = round(sum(vals) / len(vals), 1)
            print("    %-10s %3d seq  %7.0f CPU s/seq" % (fam, len(vals), sum(vals) / len(vals)))
    wall = sum(w for s in per_series.values() for _, w, _ in s.values())
    cpu = sum(c for s in per_series.values() for c, _, _ in s.values())
    est = report["sequence_cpu_seconds"]
    if "train" in est and "eval" in est:
        plan_cpu = args.plan_eval * est["eval"] + args.plan_train * est["train"]
        print("plan: %d eval + %d train sequences = %.0f CPU s: %.1f h on 2 idle cores, %.1f h at "
              "the measured %.2f cores" % (args.plan_eval, args.plan_train, plan_cpu,
                                            plan_cpu / 1.9 / 3600, plan_cpu / (cpu / wall) / 3600,
                                            cpu / wall))
        report["plan"] = {"eval": args.plan_eval, "train": args.plan_train,
                          "cpu_seconds": round(plan_cpu), "measured_cores": round(cpu / wall, 3)}
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(report, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
