#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""How far a farm chunk is from the sequential run for each preroll length (docs/farm.md).

For each method: one sequential afntool run over the first..last frames, then the last chunk
(--frames chunk_first-last) with --preroll 0..chunk_first-first, every output in float. Prints a
Markdown table: max and mean |chunked - sequential| on linear RGB, the worst and mean frame PSNR
of the chunk against the sequential run, and the chunk's mean PSNR against the reference frames
(afntool --compare: docs/metrics.md, T(x) = clip(x^(1/2.2), 0, 1)).

Usage: measure-preroll.py AFNTOOL [--seq DIR] [--frames 0-7] [--chunk-first 4] [--prerolls 0,2]
           [METHOD ...]
"""
import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def run(cmd):
    """Run afntool, raising with its stderr on failure; returns stdout."""
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join(cmd) + "\n" + r.stderr)
    return r.stdout


def pixels(path):
    """Linear RGB of a written frame, float64."""
    buf = oiio.ImageBuf(str(path))
    return np.asarray(buf.get_pixels(oiio.FLOAT), dtype=np.float64)[..., :3]


def psnrs(afntool, frames, test, ref):
    """Per-frame PSNR of `test` against `ref` (patterns) from afntool --compare --json."""
    out = json.loads(run([afntool, "-q", "--frames", frames, test, "--compare", ref, "--json"]))
    return [math.inf if f["psnr"] is None else f["psnr"] for f in out["frames"]]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("afntool")
    ap.add_argument("--seq", default=str(Path(__file__).resolve().parents[2] / "examples/sequence"))
    ap.add_argument("--frames", default="0-7")
    ap.add_argument("--chunk-first", type=int, default=4)
    ap.add_argument("--prerolls", help="comma-separated lengths (default: 0..chunk-first - first)")
    ap.add_argument("methods", nargs="*", default=["ta", "svgf", "bmfr", "afn"])
    a = ap.parse_intermixed_args()
    first, last = (int(v) for v in a.frames.split("-"))
    inp, ref = f"{a.seq}/frame.####.exr", f"{a.seq}/reference.####.exr"
    chunk = f"{a.chunk_first}-{last}"
    prerolls = ([int(v) for v in a.prerolls.split(",")] if a.prerolls
                else range(a.chunk_first - first + 1))
    print("| method | preroll | max abs | mean abs | min PSNR vs seq | mean PSNR vs seq "
          "| mean PSNR vs reference |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for m in a.methods:
            seq = f"{tmp}/{m}.seq.####.exr"
            run([a.afntool, "-q", "--frames", a.frames, inp, f"--denoise:method={m}", "-d", "float",
                 "-o", seq])
            ref_seq = np.mean(psnrs(a.afntool, chunk, seq, ref))
            print(f"| {m} | sequential | | | | | {ref_seq:.2f} |")
            for p in prerolls:
                out = f"{tmp}/{m}.p{p}.####.exr"
                run([a.afntool, "-q", "--frames", chunk, inp, "--preroll", str(p),
                     f"--denoise:method={m}", "-d", "float", "-o", out])
                diffs = [np.abs(pixels(out.replace("####", f"{f:04d}"))
                                - pixels(seq.replace("####", f"{f:04d}")))
                         for f in range(a.chunk_first, last + 1)]
                d = np.concatenate([x.ravel() for x in diffs])
                vs_seq = psnrs(a.afntool, chunk, out, seq)
                vs_ref = np.mean(psnrs(a.afntool, chunk, out, ref))
                print(f"| {m} | {p} | {d.max():.4g} | {d.mean():.4g} | {min(vs_seq):.2f} "
                      f"| {np.mean(vs_seq):.2f} | {vs_ref:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
