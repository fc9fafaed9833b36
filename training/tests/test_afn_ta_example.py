# SPDX-License-Identifier: Apache-2.0
"""The training toolkit's TA-1spp input (afn/dataset.py + afn/ta.py) against the C++ library's
``ta`` method run by afntool on the bundled Blender example sequence (8 frames, 320x180, motion
vectors, world position and normals). The C++ output is the accumulated irradiance remodulated by
max(albedo, 2^-10), so the Python side is remodulated the same way before comparing."""

import glob
import os
import subprocess
import sys

import numpy as np
import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(TRAINING)
SEQUENCE = os.path.join(ROOT, "examples", "sequence")
sys.path.insert(0, TRAINING)

oiio = pytest.importorskip("OpenImageIO")
from afn import color, dataset  # noqa: E402


def find_afntool():
    env = os.environ.get("AFNTOOL")
    if env:
        return env
    found = sorted(glob.glob(os.path.join(ROOT, "build*", "cli", "afntool")), key=os.path.getmtime)
    return found[-1] if found else None


def read_rgb(path):
    img = oiio.ImageBuf(path)
    spec = img.spec()
    names = list(spec.channelnames)
    px = img.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    return px[..., [names.index(c) for c in ("R", "G", "B")]]


def test_python_ta_equals_the_cpp_ta_on_the_example_sequence(tmp_path):
    tool = find_afntool()
    if not tool or not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("afntool not built or examples/sequence missing")
    out = str(tmp_path / "ta.####.exr")
    subprocess.run([tool, "-q", "--frames", "0-7", os.path.join(SEQUENCE, "frame.####.exr"),
                    "--denoise:method=ta", "-d", "float", "-o", out], check=True)
    scene = dataset.load_scene(SEQUENCE)
    assert scene["cta"].shape[0] == 8
    worst = 0.0
    for f in range(8):
        cpp = read_rgb(str(tmp_path / f"ta.{f:04d}.exr"))
        py = color.remodulate(scene["cta"][f], scene["albedo"][f])
        diff = np.abs(cpp - py)
        rel = diff / np.maximum(np.abs(cpp), 1e-3)
        worst = max(worst, float(diff.max()))
        assert rel.max() < 1e-5, f"frame {f}: max abs diff {diff.max()}, max rel {rel.max()}"
        if f > 0:   # the history matters: TA differs from the 1-spp frame
            assert np.abs(scene["cta"][f] - scene["c1"][f]).mean() > 1e-3
    print(f"max abs difference Python TA vs C++ TA over 8 frames: {worst:.3g}")
