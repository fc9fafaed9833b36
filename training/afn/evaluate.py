# SPDX-License-Identifier: Apache-2.0
"""Accuracy tables of afn against its baselines on held-out rendered scenes (paper Tables 1-4, 11).

    cd training && /usr/bin/python3 -m afn.evaluate --data ../data/afn-default \\
        --scenes moving_light,glass --weights results/eval-holdout/model.afnw \\
        [--ablation full=a.afnw,fusion=b.afnw,1spp=c.afnw,ta=d.afnw] [--frames 0-15] \\
        [--spp 16] [--timing 1280x720] \\
        --out ../docs/afn-evaluation.md --json results.json

A scene is a folder under --data (or an absolute path, e.g. examples/sequence) holding
frame.NNNN.exr and reference.NNNN.exr. With --spp N a scene's frames come from its sppN/ subfolder
where it has one (the afn-dataset-2 layout of docs/dataset.md: SCENE/sppN/frame.NNNN.exr beside
SCENE/reference.NNNN.exr); folders without it are read as they are. --timing WxH adds paper
Table 9: one `afntool --benchmark:size=WxH` run over every method, ms per frame on this machine.

For every scene and method (the noisy 1-spp input, ta, svgf, bmfr, nbgd, wskpn, onnd, mrkp, afn)
it runs one afntool command, ``afntool --frames F DATA/scene/frame.####.exr [--denoise:method=M] --compare
DATA/scene/reference.####.exr --json``: the denoised frames are scored in memory (no files are
written; docs/metrics.md states the metrics). A sequence's value is the mean over its frames, the
Average row the mean over scenes. A method that fails (e.g. afn without weights) is shown as "—"
with afntool's error in a footnote. Progress goes to stderr.
"""

import argparse
import datetime
import glob
import hashlib
import json
import math
import os
import shlex
import subprocess
import sys
import time

from . import afntool
from .weights import WeightsFormatError, loads

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
METHODS = [("noisy", "Noisy (1 spp)"), ("ta", "TA"), ("svgf", "SVGF"), ("bmfr", "BMFR"),
           ("nbgd", "NBGD"), ("wskpn", "WSKPN"), ("onnd", "ONND"), ("mrkp", "MR-KP"),
           ("afn", "AFN")]
# The learned baselines (nbgd, wskpn, onnd, mrkp) run with the library's built-in weights, trained
# by training/afn/baselines/train.py (nbgd, wskpn) and onnd_mrkp_train.py (onnd, mrkp) on the
# training split only (never on the evaluation scenes).
# (afntool JSON key, table title, higher is better, format)
METRICS = [("psnr", "PSNR (dB)", True, "{:.3f}"), ("ssim", "SSIM", True, "{:.4f}"),
           ("rmse", "RMSE", False, "{:.4f}"), ("smape", "SMAPE", False, "{:.4f}")]
TEMPORAL = ("tge", "Temporal-gradient error", False, "{:.5f}")
# Ablation variants in the order of the paper's Table 11.
VARIANTS = [("1spp", "1-spp only"), ("ta", "TA-1spp only"), ("fusion", "Fusion only"),
            ("full", "Fusion + refinement")]


def log(msg):
    print(f"afn.evaluate: {msg}", file=sys.stderr, flush=True)


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def weights_info(path):
    """Path, sha256 and the variant written in the archive's metadata."""
    info = {"path": path, "sha256": sha256(path)}
    try:
        with open(path, "rb") as f:
            info["variant"] = loads(f.read())[1].get("variant", "full")
    except WeightsFormatError as e:
        info["variant"] = None
        info["error"] = str(e)
    return info


def frames_found(scene_dir):
    """Frame numbers that have both a noisy frame and a reference."""
    frame_dir, ref_dir = scene_dirs(scene_dir)
    nums = []
    for p in glob.glob(os.path.join(frame_dir, "frame.[0-9][0-9][0-9][0-9].exr")):
        n = int(os.path.basename(p)[6:10])
        if os.path.exists(os.path.join(ref_dir, f"reference.{n:04d}.exr")):
            nums.append(n)
    return sorted(nums)


SPP = None   # set by main(): --spp N reads SCENE/sppN/ where a scene has it


def scene_dirs(scene_dir):
    """(folder of the noisy frames, folder of the references) of one scene."""
    if SPP is not None and os.path.isdir(os.path.join(scene_dir, f"spp{SPP}")):
        return os.path.join(scene_dir, f"spp{SPP}"), scene_dir
    return scene_dir, scene_dir


def afntool_command(args, scene, method, weights):
    frame_dir, ref_dir = scene_dirs(os.path.join(args.data, scene))
    cmd = [args.afntool, "--threads", str(args.threads), "--frames", args.scene_frames[scene]]
    if weights:
        cmd += ["--weights", weights]
    cmd.append(os.path.join(frame_dir, "frame.####.exr"))
    if method != "noisy":
        cmd.append(f"--denoise:method={method}")
    return cmd + ["--compare", os.path.join(ref_dir, "reference.####.exr"), "--json"]


def run_one(args, scene, method, weights=None, label=None):
    """Metrics of one method on one scene: {'mean', 'frames', 'seconds'} or {'error'}."""
    cmd = afntool_command(args, scene, method, weights)
    label = label or method
    t0 = time.time()
    try:
        p = subprocess.run(cmd, check=True, capture_output=True, text=True)
    except subprocess.CalledProcessError as e:
        msg = f"afntool exited with {e.returncode}: {afntool.error_text(e.stderr)}"
        log(f"{scene}: {label} FAILED: {msg}")
        return {"error": msg, "command": shlex.join(cmd)}
    try:
        out = json.loads(p.stdout)
    except json.JSONDecodeError as e:
        msg = f"afntool printed no JSON ({e}): {p.stdout[:200]!r}"
        log(f"{scene}: {label} FAILED: {msg}")
        return {"error": msg, "command": shlex.join(cmd)}
    dt = time.time() - t0
    psnr = out["mean"].get("psnr")
    log(f"{scene}: {label:12s} {len(out['frames'])} frames, PSNR "
        f"{'null' if psnr is None else f'{psnr:.3f}'} dB ({dt:.1f} s)")
    return {"mean": out["mean"], "frames": out["frames"], "seconds": round(dt, 3),
            "command": shlex.join(cmd)}


def average(results, scenes, key):
    """Mean over scenes of each metric (None where a scene has null); {'error'} if one failed."""
    runs = [results[s].get(key) for s in scenes]
    failed = [s for s, r in zip(scenes, runs) if r is None or "error" in r]
    if failed:
        return {"error": "no average: failed on " + ", ".join(f"`{s}`" for s in failed)}
    avg = {}
    for name in runs[0]["mean"]:
        vals = [r["mean"].get(name) for r in runs]
        avg[name] = None if any(v is None for v in vals) else sum(vals) / len(vals)
    return avg


def evaluate(args):
    results = {s: {} for s in args.scenes}
    for scene in args.scenes:
        for method, _ in METHODS:
            results[scene][method] = run_one(args, scene, method,
                                             args.weights if method == "afn" else None)
        for variant, path in args.ablation.items():
            if args.weights and os.path.realpath(path) == os.path.realpath(args.weights):
                results[scene]["ablation:" + variant] = results[scene]["afn"]   # same run
            else:
                results[scene]["ablation:" + variant] = run_one(args, scene, "afn", path,
                                                                f"afn[{variant}]")
    keys = [m for m, _ in METHODS] + ["ablation:" + v for v in args.ablation]
    averages = {k: average(results, args.scenes, k) for k in keys}
    return results, averages


# ---- markdown -----------------------------------------------------------------------------------

class Notes:
    """GitHub-style footnotes, one per distinct error text."""

    def __init__(self):
        self.texts = []

    def ref(self, text):
        if text not in self.texts:
            self.texts.append(text)
        return f"[^{self.texts.index(text) + 1}]"

    def lines(self):
        return [f"[^{i + 1}]: {t}" for i, t in enumerate(self.texts)]


def cell_value(run, name):
    """The number shown in a table cell, or None."""
    if run is None or "error" in run:
        return None
    v = run["mean"].get(name) if "mean" in run else run.get(name)
    return None if v is None or not math.isfinite(v) else v


def best_flags(values, fmt, higher):
    """Bold flags: the best value at display precision (ties all bold)."""
    shown = [None if v is None else float(fmt.format(v)) for v in values]
    present = [v for v in shown if v is not None]
    if not present:
        return [False] * len(values)
    best = max(present) if higher else min(present)
    return [v == best for v in shown]


def cells(runs, name, fmt, higher, notes, labels):
    values = [cell_value(r, name) for r in runs]
    out = []
    for run, v, bold, label in zip(runs, values, best_flags(values, fmt, higher), labels):
        if v is not None:
            out.append(f"**{fmt.format(v)}**" if bold else fmt.format(v))
        elif run is not None and "error" in run:
            out.append("—" + notes.ref(f"{label}: {run['error']}"))
        else:
            out.append("—" + notes.ref("null in afntool's JSON (a NaN or infinite value) in at "
                                       "least one frame or scene"))
    return out


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(r) + " |" for r in rows]


def method_labels():
    """Column titles; the noisy input's names the sample count read with --spp."""
    return [f"Noisy ({SPP} spp)" if m == "noisy" and SPP is not None else label
            for m, label in METHODS]


def scene_name(scene):
    """A scene as the tables show it: its name, or an absolute path relative to the repository."""
    if os.path.isabs(scene):
        rel = os.path.relpath(scene, REPO)
        return scene if rel.startswith("..") else rel
    return scene


def metric_table(metric, results, averages, scenes, notes):
    key, title, higher, fmt = metric
    labels = method_labels()
    rows = []
    for scene in scenes:
        runs = [results[scene][m] for m, _ in METHODS]
        rows.append([f"`{scene_name(scene)}`"] + cells(runs, key, fmt, higher, notes, labels))
    avg = [averages[m] for m, _ in METHODS]
    rows.append(["Average"] + cells(avg, key, fmt, higher, notes, labels))
    arrow = "higher is better" if higher else "lower is better"
    return [f"### {title}", "", f"({arrow}; best per row in bold)", ""] + \
        table(["Scene"] + labels, rows) + [""]


# ---- paper Table 9: time per frame ---------------------------------------------------------------

def run_timing(args):
    """One afntool benchmark run over every method at args.timing (WxH): its JSON points, the
    command and the load average before and after (the machine may be shared)."""
    methods = [m for m, _ in METHODS if m != "noisy"]
    cmd = [args.afntool, "--threads", str(args.threads), "-q",
           f"--benchmark:size={args.timing}:methods={','.join(methods)}:frames=5:warmup=1",
           "--json"]
    load0 = os.getloadavg()[0]
    try:
        p = subprocess.run(cmd, check=True, capture_output=True, text=True)
        doc = json.loads(p.stdout)
    except (subprocess.CalledProcessError, json.JSONDecodeError) as e:
        log(f"timing FAILED: {e}")
        return {"error": str(e), "command": shlex.join(cmd)}
    load1 = os.getloadavg()[0]
    log(f"timing at {args.timing}: {len(doc.get('points', []))} methods")
    return {"points": doc.get("points", []), "command": shlex.join(cmd),
            "load": [round(load0, 2), round(load1, 2)], "threads": doc.get("threads")}


def timing_table(timing):
    lines = ["### Time per frame (paper Table 9)", ""]
    if "error" in timing:
        return lines + [f"The benchmark failed: {timing['error']}", ""]
    lines += [f"One run on this machine ({timing['threads']} threads, load average "
              f"{timing['load'][0]} before, {timing['load'][1]} after: a shared machine "
              "inflates wall times, the process CPU time is the steadier figure), median of 5 "
              "frames after 1 warm-up, synthetic frames with every AOV:", "", "```sh",
              timing["command"], "```", ""]
    rows = []
    by = {p["method"]: p for p in timing["points"]}
    labels = dict(METHODS)
    for m, _ in METHODS:
        p = by.get(m)
        if p:
            size = f"{p['width']}x{p['height']}"
            rows.append([labels[m], size, f"{p['medianMs']:.1f}", f"{p['medianCpuMs']:.1f}",
                         f"{p['heapMiBPerMegapixel']:.0f}"])
    return lines + table(["Method", "Size", "ms per frame (wall)", "CPU ms per frame",
                          "Heap MiB per MP"], rows) + [""]


def ablation_table(results, averages, scenes, args, notes):
    variants = [(v, label) for v, label in VARIANTS if v in args.ablation]
    keys = ["ablation:" + v for v, _ in variants]
    labels = [label for _, label in variants]
    cols = []   # one column of cells per metric, then per scene PSNR
    for key, _, higher, fmt in METRICS:
        cols.append(cells([averages[k] for k in keys], key, fmt, higher, notes, labels))
    for scene in scenes:
        cols.append(cells([results[scene][k] for k in keys], "psnr", "{:.3f}", True, notes,
                          labels))
    header = ["Variant"] + [f"{t} (avg)" for _, t, _, _ in METRICS] + \
        [f"PSNR `{s}`" for s in scenes]

    def where(path):  # the results folder names the run; the file is always model.afnw
        return os.path.basename(os.path.dirname(os.path.abspath(path)))
    rows = [[f"{label} (`{where(args.ablation[v])}`)"] + [c[i] for c in cols]
            for i, (v, label) in enumerate(variants)]
    return ["### Ablation (paper Table 11): fusion and refinement", "",
            "Averages over the held-out scenes; best per column in bold.", ""] + \
        table(header, rows) + [""]


def weights_line(info):
    s = f"`{info['path']}` (sha256 `{info['sha256'][:12]}`, variant `{info['variant']}`)"
    return s + (f" — {info['error']}" if "error" in info else "")


def header_lines(args, meta):
    title = "# afn evaluation: accuracy on held-out scenes"
    lines = [title + (f" at {SPP} spp" if SPP is not None else ""), "",
             f"Generated {meta['date']} by:", "", "```sh", meta["command"], "```", "",
             f"- Data: `{args.data}` — {meta['data']}",
             f"- Held-out scenes: {', '.join(f'`{scene_name(s)}`' for s in args.scenes)}",
             "- Frames: " + ", ".join(f"`{scene_name(s)}` {args.scene_frames[s]}"
                                      for s in args.scenes),
             "- Noisy input: " + (f"the scenes' `spp{SPP}/` frames where they have them"
                                  if SPP is not None else "the scenes' `frame.NNNN.exr`"),
             f"- afntool: `{args.afntool}` ({meta['afntool_version']})",
             "- AFN weights: " + (weights_line(meta["weights"]) if meta["weights"] else
                                  "none given (the library's built-in weights, if any)")]
    for v, info in meta["ablation"].items():
        lines.append(f"- Ablation `{v}`: " + weights_line(info))
        if info["variant"] is None:
            lines.append("  - **warning**: the archive could not be read")
        elif info["variant"] != v:
            lines.append(f"  - **warning**: the archive says variant `{info['variant']}`, "
                         f"not `{v}`")
    lines += ["", "Metrics as `afntool --compare` computes them (docs/metrics.md): PSNR, SSIM and "
              "RMSE on the tone-mapped T(x) = clip(max(x,0)^(1/2.2), 0, 1), SMAPE on linear "
              "values (eps 1e-3). Each scene's value is the mean over its frames; Average is "
              "the mean over scenes. TA, SVGF and BMFR use afntool's default parameters.", ""]
    return lines


def markdown(args, meta, results, averages):
    notes = Notes()
    body = []
    for metric in METRICS:
        body += metric_table(metric, results, averages, args.scenes, notes)
    if any(cell_value(averages[m], "tge") is not None for m, _ in METHODS):
        body += metric_table(TEMPORAL, results, averages, args.scenes, notes)
    if args.ablation:
        body += ablation_table(results, averages, args.scenes, args, notes)
    if meta.get("timing"):
        body += timing_table(meta["timing"])
    foot = ["Notes:", ""] + notes.lines() if notes.texts else []
    return "\n".join(header_lines(args, meta) + body + foot) + "\n"


def replace_section(path, name, text):
    """The document at `path` with the block named `name` replaced by `text` (appended when the
    document has no such block, created when there is no document). Headings go one level down
    so the block sits under the document's own title."""
    begin, end = f"<!-- evaluate:{name} begin -->", f"<!-- evaluate:{name} end -->"
    body = "\n".join("#" + ln if ln.startswith("#") else ln for ln in text.splitlines())
    block = f"{begin}\n{body}\n{end}"
    old = open(path).read() if os.path.exists(path) else ""
    if begin in old and end in old.split(begin, 1)[1]:
        head, rest = old.split(begin, 1)
        return head + block + rest.split(end, 1)[1]
    return (old.rstrip("\n") + "\n\n" if old else "") + block + "\n"


# ---- command line -------------------------------------------------------------------------------

def parse_ablation(text):
    out = {}
    for item in filter(None, text.split(",")):
        name, sep, path = item.partition("=")
        if not sep or name not in dict(VARIANTS) or not path:
            raise SystemExit(f"afn.evaluate: --ablation expects VARIANT=FILE with VARIANT in "
                             f"{', '.join(v for v, _ in VARIANTS)}; got '{item}'")
        out[name] = path
    return out


def check_inputs(args):
    if not args.afntool or not os.path.isfile(args.afntool):
        raise SystemExit("afn.evaluate: afntool not found (build it, or give --afntool PATH); "
                         f"looked in {os.path.join(REPO, 'build*', 'cli')}")
    for path in ([args.weights] if args.weights else []) + list(args.ablation.values()):
        if not os.path.isfile(path):
            raise SystemExit(f"afn.evaluate: weights file not found: {path}")
    args.scene_frames = {}
    for scene in args.scenes:
        d = os.path.join(args.data, scene)
        nums = frames_found(d)
        if not nums:
            raise SystemExit(f"afn.evaluate: no frame.NNNN.exr with a reference.NNNN.exr in {d}")
        args.scene_frames[scene] = args.frames or afntool.frame_list(nums)


def data_summary(data):
    path = os.path.join(data, "manifest.json")
    if not os.path.exists(path):
        return "no manifest.json"
    with open(path) as f:
        m = json.load(f)
    size = f"{m['width']}x{m['height']}, " if "width" in m and "height" in m else ""
    keys = ["frames", "spp", "ref_spp", "seed", "blender"]
    return size + ", ".join(f"{k} {m[k]}" for k in keys if k in m)


def afntool_version(afntool):
    try:
        p = subprocess.run([afntool, "--version"], check=True, capture_output=True, text=True)
        return p.stdout.strip() or p.stderr.strip()
    except (OSError, subprocess.CalledProcessError) as e:
        return f"version unknown: {e}"


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", required=True, help="rendered dataset folder (docs/dataset.md)")
    ap.add_argument("--scenes", required=True, help="comma list of held-out scenes")
    ap.add_argument("--afntool", default=None, help="afntool binary (default: ../build*/cli)")
    ap.add_argument("--weights", default="", help="afn weights (.afnw) that never saw the scenes")
    ap.add_argument("--ablation", default="",
                    help="variant weights: full=a.afnw,fusion=b.afnw,1spp=c.afnw,ta=d.afnw")
    ap.add_argument("--frames", default="", help="frame range A-B (default: all frames found)")
    ap.add_argument("--threads", type=int, default=0, help="afntool threads (0: all cores)")
    ap.add_argument("--out", default="", help="markdown report (default: print to stdout)")
    ap.add_argument("--json", default="", help="raw numbers (per frame and mean) as JSON")
    ap.add_argument("--spp", type=int, default=None,
                    help="read each scene's noisy frames from its sppN/ folder where it has one")
    ap.add_argument("--section", default="",
                    help="NAME: update only the block between '<!-- evaluate:NAME begin/end -->' "
                    "in --out (appended if absent; headings one level down), keep the rest")
    ap.add_argument("--timing", default="",
                    help="WxH: add paper Table 9 (ms per frame of every method, one benchmark run)")
    args = ap.parse_args(argv)
    global SPP
    SPP = args.spp
    if args.section and not args.out:
        raise SystemExit("afn.evaluate: --section needs --out (the document to update)")
    args.scenes = [s for s in args.scenes.split(",") if s]
    args.ablation = parse_ablation(args.ablation)
    args.afntool = args.afntool or afntool.find_afntool()
    check_inputs(args)

    meta = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "command": "cd training && " + shlex.join([sys.executable, "-m", "afn.evaluate"] +
                                                      argv),
            "data": data_summary(args.data), "afntool_version": afntool_version(args.afntool),
            "weights": weights_info(args.weights) if args.weights else None,
            "ablation": {v: weights_info(p) for v, p in args.ablation.items()}}
    log(f"{len(args.scenes)} scenes x {len(METHODS) + len(args.ablation)} runs, "
        f"afntool {args.afntool}")
    results, averages = evaluate(args)
    if args.timing:
        meta["timing"] = run_timing(args)

    text = markdown(args, meta, results, averages)
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        if args.section:
            text = replace_section(args.out, args.section, text)
        with open(args.out + ".tmp", "w") as f:
            f.write(text)
        os.replace(args.out + ".tmp", args.out)
        log(f"wrote {args.out}")
    else:
        sys.stdout.write(text)
    if args.json:
        doc = dict(meta, data_path=args.data, scenes=args.scenes, frames=args.scene_frames,
                   afntool=args.afntool, results=results, average=averages)
        with open(args.json, "w") as f:
            json.dump(doc, f, indent=1, allow_nan=False, default=str)
        log(f"wrote {args.json}")
    return results, averages


if __name__ == "__main__":
    main()
