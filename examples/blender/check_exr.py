#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Check rendered afn EXRs: required passes present, Vector not all zero, Depth background 1e10.

Usage: /usr/bin/python3 examples/blender/check_exr.py [--reference] [--expect-motion] FILE...
``--expect-motion`` makes an all-zero Vector pass an error (a warning otherwise: a static camera
over static geometry legitimately has no motion).
Prints one summary line per file; exits 1 on the first failed check (message names the file).
"""

import sys

import numpy as np
import OpenImageIO as oiio

LAYER = "ViewLayer."
NOISY_CHANNELS = [
    "Combined.R", "Combined.G", "Combined.B", "Combined.A",
    "Denoising Albedo.R", "Denoising Albedo.G", "Denoising Albedo.B",
    "Denoising Normal.X", "Denoising Normal.Y", "Denoising Normal.Z", "Denoising Depth.Z",
    "Normal.X", "Normal.Y", "Normal.Z", "Position.X", "Position.Y", "Position.Z", "Depth.Z",
    "Vector.X", "Vector.Y", "Vector.Z", "Vector.W",
]
REFERENCE_CHANNELS = NOISY_CHANNELS[:4]
BACKGROUND_DEPTH = 1e10  # Cycles' Depth.Z where a ray escapes to the world


def fail(path, msg):
    sys.exit("check_exr ERROR: %s (%s)" % (msg, path))


def check(path, reference, expect_motion):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        fail(path, "cannot open: " + oiio.geterror())
    spec = inp.spec()
    pixels = inp.read_image(oiio.FLOAT)
    inp.close()
    names = list(spec.channelnames)
    want = REFERENCE_CHANNELS if reference else NOISY_CHANNELS
    missing = [c for c in want if LAYER + c not in names]
    if missing:
        fail(path, "missing channels " + ", ".join(missing))
    ch = {n: pixels[:, :, i] for i, n in enumerate(names)}
    rgb = np.stack([ch[LAYER + "Combined." + c] for c in "RGB"], -1)
    if not np.all(np.isfinite(rgb)):
        fail(path, "non-finite Combined values")
    summary = "%s: %dx%d %d ch, Combined mean %.4f" % (path, spec.width, spec.height, len(names),
                                                        float(rgb.mean()))
    if not reference:
        vec = np.stack([ch[LAYER + "Vector." + c] for c in "XYZW"], -1)
        if not np.any(vec != 0.0):
            if expect_motion:
                fail(path, "Vector pass is all zero (motion blur on?)")
            print("check_exr warning: Vector pass is all zero (%s)" % path)
        depth = ch[LAYER + "Depth.Z"]
        bg = depth >= 1e9
        if bg.any() and not np.allclose(depth[bg], BACKGROUND_DEPTH, rtol=1e-6):
            fail(path, "Depth background is not 1e10")
        summary += ", |Vector| max %.3f px, background %.1f%% (Depth %.3g)" % (
            float(np.abs(vec).max()), 100.0 * bg.mean(), float(depth[bg].max()) if bg.any() else 0)
    print(summary)


def main(argv):
    reference = "--reference" in argv
    expect_motion = "--expect-motion" in argv
    files = [a for a in argv if not a.startswith("--")]
    if not files:
        sys.exit(__doc__)
    for path in files:
        check(path, reference, expect_motion)


if __name__ == "__main__":
    main(sys.argv[1:])
