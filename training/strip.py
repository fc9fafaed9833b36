#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Side-by-side strip of denoised frames: rows are frames, columns are labelled image sequences.

Usage: /usr/bin/python3 training/strip.py OUT.png --frames 4,5,6 \\
           LABEL=PATTERN [LABEL=PATTERN ...] [--crop X,Y,W,H] [--scale 2]

PATTERN is a path with ``####`` for the frame number (e.g. ``out/afn.####.exr``). The first three
channels of each EXR (or its ``ViewLayer.Combined`` RGB, for the renderer's own files) are converted
from linear to sRGB with OpenColorIO's built-in transform in OpenImageIO, optionally cropped and
enlarged (nearest neighbour, so noise stays visible), and labelled when DejaVu Sans is installed.
"""

import argparse
import sys

import OpenImageIO as oiio

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
COMBINED = ["ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"]


def load(path, crop, scale):
    src = oiio.ImageBuf(path)
    if src.has_error:
        sys.exit("strip ERROR: cannot read %s: %s" % (path, src.geterror()))
    names = list(src.spec().channelnames)
    chans = tuple(names.index(c) for c in COMBINED) if all(c in names for c in COMBINED) \
        else (0, 1, 2)
    rgb = oiio.ImageBufAlgo.channels(src, chans)
    if crop:
        x, y, w, h = crop
        rgb = oiio.ImageBufAlgo.cut(rgb, oiio.ROI(x, x + w, y, y + h))
    srgb = oiio.ImageBufAlgo.colorconvert(rgb, "linear", "sRGB")
    if scale > 1:
        spec = srgb.spec()
        srgb = oiio.ImageBufAlgo.resize(
            srgb, "box", roi=oiio.ROI(0, spec.width * scale, 0, spec.height * scale, 0, 1, 0, 3))
    return srgb


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("columns", nargs="+", help="LABEL=PATTERN")
    ap.add_argument("--frames", required=True, help="comma list of frame numbers")
    ap.add_argument("--crop", help="X,Y,W,H")
    ap.add_argument("--scale", type=int, default=1)
    args = ap.parse_args(argv)
    crop = [int(v) for v in args.crop.split(",")] if args.crop else None
    cols = [c.partition("=")[::2] for c in args.columns]
    frames = [int(f) for f in args.frames.split(",")]
    tiles = [[load(p.replace("####", "%04d" % f), crop, args.scale) for _, p in cols]
             for f in frames]
    tw, th = tiles[0][0].spec().width, tiles[0][0].spec().height
    label_h = 18
    sheet = oiio.ImageBuf(oiio.ImageSpec(tw * len(cols), label_h + th * len(frames), 3, "uint8"))
    for j, (label, _) in enumerate(cols):
        oiio.ImageBufAlgo.render_text(sheet, j * tw + 4, 14, label, 13, FONT, (1, 1, 1))
    for i, row in enumerate(tiles):
        for j, t in enumerate(row):
            oiio.ImageBufAlgo.paste(sheet, j * tw, label_h + i * th, 0, 0, t)
            if j == 0:
                oiio.ImageBufAlgo.render_text(sheet, j * tw + 4, label_h + i * th + 14,
                                              "frame %d" % frames[i], 12, FONT, (1, 1, 0))
    if not sheet.write(args.out):
        sys.exit("strip ERROR: cannot write %s: %s" % (args.out, sheet.geterror()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
