# SPDX-License-Identifier: Apache-2.0
"""error_bands.py: a smooth offset is low band, a pixel checkerboard high band, e = low + high."""

import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
oiio = pytest.importorskip("OpenImageIO")
import error_bands  # noqa: E402


def test_offset_is_low_and_checkerboard_is_high():
    ref = np.full((40, 48, 3), 0.25, np.float32)
    t = 0.25 ** (1 / 2.2)
    brighter = np.full_like(ref, (t + 0.05) ** 2.2)            # T(out) - T(ref) = 0.05 everywhere
    full, low, high = error_bands.bands(brighter, ref, 4.0)
    assert full == pytest.approx(10 * np.log10(1 / 0.05 ** 2), abs=1e-3)
    assert low == pytest.approx(full, abs=1e-3) and high > 100    # all of it is bias
    yy, xx = np.mgrid[:40, :48]
    sign = np.where((yy + xx) % 2 == 0, 1.0, -1.0)[..., None]
    noisy = (t + 0.05 * sign) ** 2.2 * np.ones_like(ref)
    full, low, high = error_bands.bands(noisy.astype(np.float32), ref, 4.0)
    assert high == pytest.approx(full, abs=0.05) and low > full + 25  # all of it is fine noise


def test_blur_keeps_constants_and_splits_exactly():
    rng = np.random.default_rng(0)
    e = rng.normal(size=(17, 23, 3))
    assert np.allclose(error_bands.gaussian_blur(np.full((9, 11, 3), 2.0), 3.0), 2.0)
    low = error_bands.gaussian_blur(e, 2.0)
    assert low.shape == e.shape and low.std() < 0.5 * e.std()


def test_cli_reads_renderer_channels(tmp_path, capsys):
    def write(path, names, value):
        spec = oiio.ImageSpec(8, 6, len(names), "float")
        spec.channelnames = names
        buf = oiio.ImageBuf(spec)
        buf.set_pixels(oiio.ROI(), np.full((6, 8, len(names)), value, np.float32))
        assert buf.write(str(path))
    write(tmp_path / "out.0003.exr", ["R", "G", "B"], 0.5)
    write(tmp_path / "ref.0003.exr", ["ViewLayer.Combined.R", "ViewLayer.Combined.G",
                                      "ViewLayer.Combined.B", "ViewLayer.Combined.A"], 0.5)
    assert error_bands.main([str(tmp_path / "out.####.exr"), str(tmp_path / "ref.####.exr"),
                             "--frames", "3"]) == 0
    assert "mean (sigma 4): PSNR 120.000" in capsys.readouterr().out
    write(tmp_path / "bad.0003.exr", ["X", "Y"], 0.5)
    with pytest.raises(SystemExit, match="no RGB"):
        error_bands.main([str(tmp_path / "bad.####.exr"), str(tmp_path / "ref.####.exr"),
                          "--frames", "3"])
