#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Contact sheet of a rendered dataset: one labelled frame per scene, sRGB PNG.

Usage: /usr/bin/python3 training/contact_sheet.py DATASET_DIR OUT.png [--frame N] [--noisy]
       [--columns 4] [--limit N] [--per-family K]

DATASET_DIR is a ``render-dataset`` or a ``generate-dataset`` output.

Uses each scene's reference (or, with ``--noisy``, its 1-spp frame) of frame N (default 0),
converts linear to sRGB with OpenColorIO's built-in transform in OpenImageIO, and writes the tiles
in name order. Labels need a TrueType font (DejaVu Sans from Debian's fonts-dejavu-core); without
it the tiles are left unlabelled.
"""

import argparse
import json
import os
import sys

import OpenImageIO as oiio

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
RGB = ["ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"]


def tile(path, label):
    """Read Combined RGB of ``path``, convert to sRGB and label it; return an ImageBuf."""
    src = oiio.ImageBuf(path)
    if src.has_error:
        raise RuntimeError("%s (%s)" % (src.geterror(), path))
    rgb = oiio.ImageBufAlgo.channels(src, tuple(RGB))
    if rgb.has_error:
        raise RuntimeError("no Combined RGB: %s (%s)" % (rgb.geterror(), path))
    srgb = oiio.ImageBufAlgo.colorconvert(rgb, "linear", "sRGB")
    if os.path.exists(FONT):
        size = max(10, srgb.spec().height // 12)
        oiio.ImageBufAlgo.render_text(srgb, 4, size + 2, label, size, FONT, (1, 1, 1))
    return srgb


def main(argv):
    ap = argparse.ArgumentParser(prog="contact_sheet.py")
    ap.add_argument("dataset")
    ap.add_argument("out")
    ap.add_argument("--frame", type=int, default=0)
    ap.add_argument("--noisy", action="store_true")
    ap.add_argument("--columns", type=int, default=4)
    ap.add_argument("--limit", type=int, default=0, help="at most this many scenes (name order)")
    ap.add_argument("--per-family", type=int, default=0,
                    help="generated sets: the K lowest seeds of each family")
    args = ap.parse_args(argv)
    with open(os.path.join(args.dataset, "manifest.json")) as fh:
        manifest = json.load(fh)
    # afn-dataset-1 (render-dataset) lists "scenes"; afn-dataset-2 (generate-dataset) lists
    # "sequences", whose frames and references lie in spp<S>/ (the lowest S is shown).
    records = manifest.get("scenes") or manifest.get("sequences", {})
    if args.per_family:
        seen = {}
        for name, rec in sorted(records.items(), key=lambda kv: (kv[1]["seed"], kv[0])):
            seen.setdefault(rec.get("family"), []).append(name)
        keep = {n for names in seen.values() for n in names[:args.per_family]}
        records = {n: r for n, r in records.items() if n in keep}
    if args.limit:
        records = dict(sorted(records.items())[:args.limit])
    tiles = []
    for name, rec in sorted(records.items()):
        folder = os.path.join(args.dataset, rec["dir"])
        if "levels" in rec:  # generated: the lowest level's frame and the reference it is scored by
            folder = os.path.join(folder, "spp%d" % min(rec["levels"]))
        path = os.path.join(folder, "%s.%04d.exr" % ("frame" if args.noisy else "reference",
                                                    args.frame))
        if os.path.exists(path):
            tiles.append(tile(path, name))
    if not tiles:
        sys.exit("contact_sheet ERROR: no scenes in %s" % args.dataset)
    w, h = tiles[0].spec().width, tiles[0].spec().height
    cols = min(args.columns, len(tiles))
    rows = (len(tiles) + cols - 1) // cols
    sheet = oiio.ImageBuf(oiio.ImageSpec(w * cols, h * rows, 3, oiio.FLOAT))
    for i, t in enumerate(tiles):
        oiio.ImageBufAlgo.paste(sheet, (i % cols) * w, (i // cols) * h, 0, 0, t)
    if not sheet.write(args.out, oiio.UINT8):
        sys.exit("contact_sheet ERROR: %s (%s)" % (sheet.geterror(), args.out))
    print("contact_sheet: %d scenes -> %s" % (len(tiles), args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
