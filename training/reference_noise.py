#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Measure how noisy dataset references are: PSNR of each reference against an independent one.

Usage: /usr/bin/python3 training/reference_noise.py DIR_A DIR_B [--json OUT.json]

DIR_A and DIR_B are two ``render-dataset`` outputs of the same scenes, frames, height and seed, DIR_B
with more reference samples (e.g. 4x) and another ``--ref-seed-offset`` so its noise is independent
(same offset would reuse the first samples and overstate agreement). For every scene and frame both
hold, prints PSNR (peak 1, linear RGB clamped to [0, 1]) and relative MSE (mean of
(a - b)^2 / (b^2 + 0.01)) of A's reference against B's.

If A has S samples and B has k*S, the error variance of the pair is (1 + 1/k) times A's own, so
PSNR(A vs truth) is about PSNR(A vs B) + 10*log10(1 + 1/k) dB (0.97 dB for k = 4).
"""

import json
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio

RGB = ["ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"]


def read_rgb(path):
    """Combined RGB of a reference EXR as float32 (H, W, 3)."""
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise RuntimeError("%s (%s)" % (buf.geterror(), path))
    names = list(buf.spec().channelnames)
    missing = [c for c in RGB if c not in names]
    if missing:
        raise RuntimeError("missing %s (%s)" % (", ".join(missing), path))
    pixels = buf.get_pixels(oiio.FLOAT)
    return np.stack([pixels[:, :, names.index(c)] for c in RGB], -1)


def compare(a, b):
    """(PSNR in dB with peak 1 on clamped values, relative MSE) of ``a`` against ``b``."""
    mse = float(np.mean((np.clip(a, 0, 1) - np.clip(b, 0, 1)) ** 2))
    psnr = math.inf if mse == 0 else 10.0 * math.log10(1.0 / mse)
    rel = float(np.mean((a - b) ** 2 / (b * b + 0.01)))
    return psnr, rel


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    dir_a, dir_b = argv[0], argv[1]
    out_json = argv[argv.index("--json") + 1] if "--json" in argv else None
    man_a = json.load(open(os.path.join(dir_a, "manifest.json")))
    man_b = json.load(open(os.path.join(dir_b, "manifest.json")))
    rows = []
    for scene in sorted(set(man_a["scenes"]) & set(man_b["scenes"])):
        frames = min(man_a["scenes"][scene]["frames"], man_b["scenes"][scene]["frames"])
        for f in range(frames):
            name = "reference.%04d.exr" % f
            pa, pb = os.path.join(dir_a, scene, name), os.path.join(dir_b, scene, name)
            if not (os.path.exists(pa) and os.path.exists(pb)):
                continue
            psnr, rel = compare(read_rgb(pa), read_rgb(pb))
            rows.append({"scene": scene, "frame": f, "spp_a": man_a["ref_spp"],
                         "spp_b": man_b["ref_spp"], "psnr_db": round(psnr, 2),
                         "relmse": round(rel, 6)})
            print("%-16s frame %d  %5d vs %5d spp  PSNR %6.2f dB  relMSE %.5f"
                  % (scene, f, man_a["ref_spp"], man_b["ref_spp"], psnr, rel))
    if out_json:
        with open(out_json, "w") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
