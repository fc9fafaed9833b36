#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Write the seed EXRs of fuzz_exr_reader into tests/fuzz/corpus/fuzz_exr_reader.

Small files (a few hundred bytes each) covering what the reader has to handle: renderer layer
conventions (Blender, Arnold, V-Ray, RenderMan, generic), multi-part files with named parts and a
part of another data window, data windows offset from and larger than the display window, channel
types (half, float, uint, mixed), tiled and mip-mapped parts, every OpenEXR compression, values
beyond half range, NaN/Inf, and 1-pixel-wide images. Run with the system Python (python3-openimageio):

    /usr/bin/python3 tests/fuzz/seeds/make_exr_seeds.py
"""
import os
import sys

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "corpus", "fuzz_exr_reader")


def pixels(w, h, n, seed, scale=1.0):
    rng = np.random.default_rng(seed)
    return (rng.random((h, w, n), dtype=np.float32) * scale).astype(np.float32)


def spec_for(w, h, names, fmt=oiio.HALF, formats=None, compression="zip", window=None, name=None,
             attrs=None, tile=None):
    spec = oiio.ImageSpec(w, h, len(names), fmt)
    spec.channelnames = tuple(names)
    if formats:
        spec.channelformats = tuple(formats)
    spec.attribute("compression", compression)
    if window:
        spec.x, spec.y = window[0], window[1]
        spec.full_x, spec.full_y, spec.full_width, spec.full_height = window[2:]
    if name:
        spec.attribute("name", name)
    if tile:
        spec.tile_width, spec.tile_height = tile
    for k, v in (attrs or {}).items():
        spec.attribute(k, v)
    return spec


def write(name, specs, planes):
    path = os.path.join(OUT, name)
    out = oiio.ImageOutput.create(path)
    if not out or not out.open(path, specs if len(specs) > 1 else specs[0]):
        sys.exit(f"cannot write {path}: {oiio.geterror()}")
    for i, (spec, data) in enumerate(zip(specs, planes)):
        if i > 0 and not out.open(path, spec, "AppendSubimage"):
            sys.exit(f"cannot append to {path}: {out.geterror()}")
        if not out.write_image(data):
            sys.exit(f"cannot write pixels of {path}: {out.geterror()}")
    out.close()


def layered(prefix, layers):
    names = []
    for layer, comps in layers:
        names += [f"{prefix}{layer}.{c}" if layer else c for c in comps]
    return names


def main():
    os.makedirs(OUT, exist_ok=True)
    w, h = 8, 6
    rgb = ["R", "G", "B"]
    # Renderer conventions, one layered single-part file each.
    blender = layered("ViewLayer.", [("Combined", "RGBA"), ("Denoising Albedo", rgb),
                                      ("Denoising Normal", "XYZ"), ("Denoising Depth", "Z"),
                                      ("Vector", "XYZW"), ("Position", "XYZ")])
    write("blender_layers.exr", [spec_for(w, h, blender, oiio.FLOAT,
                                          attrs={"cycles.ViewLayer.samples": "1"})],
          [pixels(w, h, len(blender), 1)])
    arnold = ["R", "G", "B", "A"] + layered("", [("diffuse_albedo", rgb), ("N", rgb), ("P", rgb),
                                                  ("motionvector", "RG")]) + ["Z"]
    write("arnold.exr", [spec_for(w, h, arnold, attrs={"arnold/version": "7"})],
          [pixels(w, h, len(arnold), 2)])
    vray = ["R", "G", "B", "A"] + layered("", [("diffuse", rgb), ("normals", "XYZ"),
                                                ("zDepth", "Y"), ("velocity", "XY")])
    write("vray.exr", [spec_for(w, h, vray, attrs={"software": "V-Ray"})],
          [pixels(w, h, len(vray), 3)])
    prman = layered("", [("Ci", rgb), ("a", ["R"]), ("albedo", rgb), ("normal", "XYZ"),
                         ("z", "Z"), ("backward", "XY"), ("mse", rgb)])
    write("renderman.exr", [spec_for(w, h, prman, attrs={"Software": "RenderMan"})],
          [pixels(w, h, len(prman), 4)])
    # Multi-part: named parts, one of another data window and type.
    parts = [("rgba", ["R", "G", "B", "A"]), ("albedo", rgb), ("normal", ["X", "Y", "Z"]),
             ("depth", ["Z"]), ("motion", ["X", "Y"])]
    specs = [spec_for(w, h, c, name=n) for n, c in parts]
    specs[3] = spec_for(w, h, ["Z"], oiio.FLOAT, name="depth", window=(2, 1, 0, 0, w, h))
    write("multipart.exr", specs, [pixels(w, h, len(c), 10 + i) for i, (_, c) in enumerate(parts)])
    # Windows: data window offset inside, outside and larger than the display window.
    for i, win in enumerate([(3, -2, 0, 0, 16, 16), (-4, -4, 0, 0, 4, 4), (100, 50, 0, 0, 8, 6)]):
        write(f"window_{i}.exr", [spec_for(w, h, rgb, window=win)], [pixels(w, h, 3, 20 + i)])
    # Channel types: mixed half/float/uint, and an all-uint id image.
    names = ["R", "G", "B", "A", "id", "Z"]
    fmts = [oiio.HALF, oiio.FLOAT, oiio.HALF, oiio.HALF, oiio.UINT, oiio.FLOAT]
    data = pixels(w, h, len(names), 30)
    data[..., 4] = np.floor(data[..., 4] * 1000)
    write("mixed_types.exr", [spec_for(w, h, names, formats=fmts)], [data])
    # Tiled, with tiles that do not divide the image.
    write("tiled.exr", [spec_for(w, h, rgb, tile=(3, 5))], [pixels(w, h, 3, 31)])
    # Every compression.
    for comp in ["none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"]:
        write(f"compression_{comp}.exr", [spec_for(w, h, rgb, compression=comp)],
              [pixels(w, h, 3, 40)])
    # Values: beyond half range (fireflies of 1e6), NaN and Inf, denormals.
    data = pixels(w, h, 3, 50)
    data[2, 3, :] = 1e6
    data[4, 1, 0] = 70000.0
    write("firefly_float.exr", [spec_for(w, h, rgb, oiio.FLOAT)], [data])
    data = pixels(w, h, 4, 51)
    data[0, 0, 0] = np.nan
    data[1, 1, 1] = np.inf
    data[2, 2, 2] = -np.inf
    data[3, 3, 3] = 1e-42
    write("nonfinite.exr", [spec_for(w, h, ["R", "G", "B", "A"], oiio.FLOAT)], [data])
    # Shapes: a single pixel, a single column, a luminance-only image.
    write("one_pixel.exr", [spec_for(1, 1, rgb)], [pixels(1, 1, 3, 60)])
    write("column.exr", [spec_for(1, 7, ["R", "G", "B", "A"])], [pixels(1, 7, 4, 61)])
    write("luminance.exr", [spec_for(w, h, ["Y"])], [pixels(w, h, 1, 62)])
    for name in sorted(os.listdir(OUT)):
        print(f"{os.path.getsize(os.path.join(OUT, name)):6d}  {name}")


if __name__ == "__main__":
    main()
