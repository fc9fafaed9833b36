#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Split a denoiser's error into a low and a high spatial-frequency band.

Usage: /usr/bin/python3 training/error_bands.py OUT.####.exr REF.####.exr --frames 0-7 [--sigma 4]
       [--json OUT.json]

PSNR alone does not say what an error looks like: a smooth bias (a region a little too dark) and
residual noise of a few pixels (blotches, grain) can cost the same. On the tone-mapped images
(T(x) = clip(max(x,0)^(1/2.2), 0, 1), as ``afntool --compare``), the error e = T(out) - T(ref) is
split by a Gaussian of `sigma` pixels into low = G*e (bias, smudges larger than sigma) and
high = e - low (noise, blotches and edges at scales below it); e = low + high. Prints the PSNR of
e, low and high per frame and their means (higher is better: 10 log10(1 / mean square)).

The RGB channels are R, G, B or the first ``*.R, *.G, *.B`` triple (a renderer's beauty, e.g.
Blender's ``ViewLayer.Combined``).
"""

import argparse
import json
import math
import sys

import numpy as np
import OpenImageIO as oiio


def read_rgb(path):
    """(H, W, 3) float32 RGB of an image (R,G,B or the first *.R/*.G/*.B triple)."""
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise SystemExit(f"error_bands: {path}: {buf.geterror()}")
    names = list(buf.spec().channelnames)
    px = buf.get_pixels(oiio.FLOAT)
    for n in names:
        if n == "R" or n.endswith(".R"):
            prefix = n[:-1]
            triple = [prefix + c for c in "RGB"]
            if all(t in names for t in triple):
                return np.stack([px[..., names.index(t)] for t in triple], -1)
    raise SystemExit(f"error_bands: {path}: no RGB channels (has {', '.join(names)})")


def tonemap(x):
    return np.clip(np.maximum(x, 0.0) ** (1.0 / 2.2), 0.0, 1.0)


def gaussian_blur(img, sigma):
    """Separable Gaussian of (H, W, C), edges replicated, radius 3 sigma."""
    r = max(1, int(math.ceil(3 * sigma)))
    x = np.arange(-r, r + 1, dtype=np.float64)
    g = np.exp(-x * x / (2 * sigma * sigma))
    g /= g.sum()
    h, w = img.shape[:2]
    padded = np.pad(img.astype(np.float64), ((r, r), (r, r), (0, 0)), mode="edge")
    along_x = sum(g[i] * padded[:, i:i + w] for i in range(2 * r + 1))      # (H + 2r, W, C)
    return sum(g[i] * along_x[i:i + h] for i in range(2 * r + 1))           # (H, W, C)


def psnr(e):
    return 10.0 * math.log10(1.0 / max(float(np.mean(e * e)), 1e-12))


def bands(out, ref, sigma):
    """(PSNR of the whole error, of its low band, of its high band) of two (H, W, 3) images."""
    e = tonemap(out).astype(np.float64) - tonemap(ref).astype(np.float64)
    low = gaussian_blur(e, sigma)
    return psnr(e), psnr(low), psnr(e - low)


def frame_range(text):
    a, _, b = text.partition("-")
    return list(range(int(a), int(b or a) + 1))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="denoised frames, #### for the frame number")
    ap.add_argument("ref", help="reference frames, #### for the frame number")
    ap.add_argument("--frames", required=True, help="first-last, e.g. 0-7")
    ap.add_argument("--sigma", type=float, default=4.0, help="Gaussian sigma in pixels (default 4)")
    ap.add_argument("--json", default="", help="also write the figures here")
    args = ap.parse_args(argv)
    rows = []
    for n in frame_range(args.frames):
        o = read_rgb(args.out.replace("####", f"{n:04d}"))
        r = read_rgb(args.ref.replace("####", f"{n:04d}"))
        if o.shape != r.shape:
            raise SystemExit(f"error_bands: frame {n}: {o.shape[1]}x{o.shape[0]} output against a "
                             f"{r.shape[1]}x{r.shape[0]} reference")
        rows.append(bands(o, r, args.sigma))
        print(f"frame {n}: PSNR {rows[-1][0]:.3f}  low {rows[-1][1]:.3f}  high {rows[-1][2]:.3f}")
    mean = np.mean(rows, 0)
    print(f"mean (sigma {args.sigma:g}): PSNR {mean[0]:.3f}  low {mean[1]:.3f}  high {mean[2]:.3f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"sigma": args.sigma, "frames": [dict(zip(("psnr", "low", "high"), r))
                                                       for r in rows],
                       "mean": dict(zip(("psnr", "low", "high"), mean.tolist()))}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
