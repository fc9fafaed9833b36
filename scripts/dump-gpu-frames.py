#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write frames of the bundled Blender sequence as raw float planes for the GPU check.

The GPU test (tests/gpu/test_afn_cuda.cpp, CudaAfn.ParityOnTheBlenderSequence) runs on a machine
without OpenImageIO; scripts/make-gpu-bundle.sh calls this to put the frames into the bundle.
Format of each frame.NNNN.afnraw (little-endian): the 8 bytes "AFNRAW01", int32 width, int32
height, then the passes color (3), albedo (3), normal (3), depth (1), position (3), motion (2):
each width * height * channels float32, interleaved. Usage:
    /usr/bin/python3 scripts/dump-gpu-frames.py EXAMPLES_DIR OUT_DIR [FRAMES (default 4)]
"""
import os
import struct
import sys

import OpenImageIO as oiio

PASSES = [("Combined", "RGB"), ("Denoising Albedo", "RGB"), ("Normal", "XYZ"), ("Depth", "Z"),
          ("Position", "XYZ"), ("Vector", "XY")]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    examples, out = sys.argv[1], sys.argv[2]
    frames = int(sys.argv[3]) if len(sys.argv) == 4 else 4
    os.makedirs(out, exist_ok=True)
    for k in range(frames):
        path = os.path.join(examples, "sequence", f"frame.{k:04d}.exr")
        image = oiio.ImageInput.open(path)
        if not image:
            sys.exit(f"dump-gpu-frames: cannot read {path}: {oiio.geterror()}")
        spec = image.spec()
        pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
        image.close()
        data = [struct.pack("<8sii", b"AFNRAW01", spec.width, spec.height)]
        for name, comps in PASSES:
            indices = [spec.channelindex(f"ViewLayer.{name}.{c}") for c in comps]
            if min(indices) < 0:
                sys.exit(f"dump-gpu-frames: {path} has no pass {name}")
            data.append(pixels[:, :, indices].astype("<f4").tobytes())
        target = os.path.join(out, f"frame.{k:04d}.afnraw")
        with open(target + ".part", "wb") as f:
            f.write(b"".join(data))
        os.replace(target + ".part", target)
    print(f"dump-gpu-frames: wrote {frames} frames to {out}")


if __name__ == "__main__":
    main()
