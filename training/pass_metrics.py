#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Accuracy of denoised light-path passes (docs/passes.md).

Usage: /usr/bin/python3 training/pass_metrics.py NOISY.####.exr DENOISED.####.exr REF.####.exr
       --frames 0-7 [--passes DiffDir,DiffInd,GlossDir,GlossInd] [--afntool build/cli/afntool]
       [--json OUT.json]

NOISY: the renderer's frames; DENOISED: ``afntool ... --denoise:method=M:passes=all --keep-aovs``
outputs (the denoised passes under their own names, the denoised beauty as R,G,B); REF: high-spp
renders of the same frames with the same passes. Per pass and frame: PSNR of the noisy and of the
denoised pass against the reference pass, on T(x) = clip(max(x,0)^(1/2.2), 0, 1) of the pass's own
values (afn's metrics, docs/metrics.md), averaged over the frames. The recomposition PSNR (the
denoised passes rebuilt by the renderer's formula against the denoised beauty) is afntool's
(``--info --json``: lightPasses.recompositionPsnr), so the formula is the one afntool uses.
"""

import argparse
import json
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

from error_bands import frame_range, psnr as psnr_of_error, tonemap


def read_layers(path):
    """{channel name: (H, W) float32} of an image."""
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise SystemExit(f"pass_metrics: {path}: {buf.geterror()}")
    names = list(buf.spec().channelnames)
    px = buf.get_pixels(oiio.FLOAT)
    return {n: px[..., i] for i, n in enumerate(names)}


def layer_rgb(channels, name, path):
    """(H, W, 3) of the layer whose channels end in '<name>.R/G/B'."""
    for n in channels:
        if n.endswith("." + name + ".R") or n == name + ".R":
            prefix = n[:-1]
            return np.stack([channels[prefix + c] for c in "RGB"], -1)
    raise SystemExit(f"pass_metrics: {path}: no layer {name} with R,G,B")


def psnr(a, b):
    return psnr_of_error(tonemap(a).astype(np.float64) - tonemap(b).astype(np.float64))


def expand(pattern, f):
    return pattern.replace("####", "%04d" % f)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("noisy")
    ap.add_argument("denoised")
    ap.add_argument("ref")
    ap.add_argument("--frames", required=True)
    ap.add_argument("--passes", default="DiffDir,DiffInd,GlossDir,GlossInd")
    ap.add_argument("--afntool", default="build/cli/afntool")
    ap.add_argument("--json", default="")
    a = ap.parse_args(argv)
    names = a.passes.split(",")
    frames = frame_range(a.frames)
    rows = {n: {"noisy": [], "denoised": []} for n in names}
    recomposition = []
    for f in frames:
        paths = [expand(p, f) for p in (a.noisy, a.denoised, a.ref)]
        noisy, den, ref = (read_layers(p) for p in paths)
        for n in names:
            r = layer_rgb(ref, n, paths[2])
            rows[n]["noisy"].append(psnr(layer_rgb(noisy, n, paths[0]), r))
            rows[n]["denoised"].append(psnr(layer_rgb(den, n, paths[1]), r))
        info = json.loads(subprocess.run([a.afntool, "--info", "--json", paths[1]], check=True,
                                         capture_output=True, text=True).stdout)
        value = info["lightPasses"].get("recompositionPsnr")
        recomposition.append(float("inf") if value is None else value)  # null: identical
    out = {"frames": frames, "passes": {}, "recompositionPsnr": recomposition,
           "recompositionPsnrMin": min(recomposition)}
    print("%-10s %12s %14s %8s" % ("pass", "noisy (dB)", "denoised (dB)", "gain"))
    for n in names:
        nm, dm = float(np.mean(rows[n]["noisy"])), float(np.mean(rows[n]["denoised"]))
        out["passes"][n] = {"noisy": nm, "denoised": dm, "gain": dm - nm,
                            "perFrame": rows[n]}
        print("%-10s %12.2f %14.2f %+8.2f" % (n, nm, dm, dm - nm))
    print("recomposition of the denoised passes against the denoised beauty: min %.1f dB "
          "(per frame %s)" % (min(recomposition), ", ".join("%.1f" % r for r in recomposition)))
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(out, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
