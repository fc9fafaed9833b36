#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Measure how noisy dataset references are: PSNR of each reference against an independent one.

Usage: /usr/bin/python3 training/reference_noise.py DIR_A DIR_B [--json OUT.json]
       /usr/bin/python3 training/reference_noise.py --parts DATASET [--json OUT.json]

DIR_A and DIR_B are two ``render-dataset`` outputs of the same scenes, frames, height and seed, DIR_B
with more reference samples (e.g. 4x) and another ``--ref-seed-offset`` so its noise is independent
(same offset would reuse the first samples and overstate agreement). For every scene and frame both
hold, prints PSNR (peak 1, linear RGB clamped to [0, 1]) and relative MSE (mean of
(a - b)^2 / (b^2 + 0.01)) of A's reference against B's.

If A has S samples and B has k*S, the error variance of the pair is (1 + 1/k) times A's own, so
PSNR(A vs truth) is about PSNR(A vs B) + 10*log10(1 + 1/k) dB (0.97 dB for k = 4).

``--parts`` measures a ``generate-dataset`` output whose evaluation references are averages of K
independent parts (``reference_partK.NNNN.exr``): part 0 against part 1 has twice one part's error
variance and the average has 1/K of it, so PSNR(average vs truth) is about PSNR(part 0 vs part 1) +
10*log10(2K) dB (6.02 dB for K = 2). It also prints the PSNR of each input level against the
averaged reference, for scale.
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


def parts_noise(root):
    """Rows of residual-noise estimates for every sequence with averaged reference parts."""
    manifest = json.load(open(os.path.join(root, "manifest.json")))
    rows = []
    for name, rec in sorted(manifest.get("sequences", {}).items()):
        k = rec.get("reference_parts", 1)
        if k < 2:
            continue
        seq = os.path.join(root, rec["dir"])
        frames = sorted(f[len("reference_part0."):-4] for f in os.listdir(seq)
                        if f.startswith("reference_part0.") and f.endswith(".exr"))
        for n in frames:
            ref = read_rgb(os.path.join(seq, "reference.%s.exr" % n))
            psnr, rel = compare(read_rgb(os.path.join(seq, "reference_part0.%s.exr" % n)),
                                read_rgb(os.path.join(seq, "reference_part1.%s.exr" % n)))
            row = {"sequence": name, "frame": int(n), "reference_spp": rec["reference_spp"],
                   "parts": k, "part_vs_part_psnr_db": round(psnr, 2), "part_relmse": round(rel, 6),
                   "reference_psnr_db": round(psnr + 10.0 * math.log10(2 * k), 2)}
            for spp in rec["levels"]:
                frame = os.path.join(seq, "spp%d" % spp, "frame.%s.exr" % n)
                row["input_%dspp_psnr_db" % spp] = round(compare(read_rgb(frame), ref)[0], 2)
            rows.append(row)
            print("%-22s frame %s  parts %.2f dB -> %d-spp reference ~%.2f dB  inputs %s"
                  % (name, n, psnr, rec["reference_spp"], row["reference_psnr_db"],
                     ", ".join("%s %.2f" % (key[6:-8], v) for key, v in row.items()
                               if key.startswith("input_"))))
    return rows


def main(argv):
    if len(argv) >= 2 and argv[0] == "--parts":
        rows = parts_noise(argv[1])
        if "--json" in argv:
            with open(argv[argv.index("--json") + 1], "w") as fh:
                json.dump(rows, fh, indent=1)
        return 0
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
