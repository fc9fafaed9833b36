# SPDX-License-Identifier: Apache-2.0
"""training/eval_history.py's argument and output parsing, and training/strip.py on tiny EXRs."""

import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import eval_history  # noqa: E402


def test_variant_specs_become_denoise_arguments():
    assert eval_history.denoise_arg("ta") == "--denoise:method=ta"
    assert eval_history.denoise_arg("bmfr/antilag=0/detail=off") == \
        "--denoise:method=bmfr:antilag=0:detail=off"


def test_mean_psnr_is_read_from_the_compare_table():
    text = ("frame psnr ssim\n0 20.5 0.5\nmean         28.3369     0.930416    0.0384108\n"
            "(PSNR/SSIM ...)\n")
    assert eval_history.mean_psnr(text) == pytest.approx(28.3369)
    with pytest.raises(SystemExit):
        eval_history.mean_psnr("no table here")


def test_a_missing_sequence_is_a_clear_error(tmp_path):
    res = subprocess.run([sys.executable, os.path.join(HERE, "..", "eval_history.py"),
                          "--data", str(tmp_path), "--scenes", "nothing", "--spp", "1",
                          "--variants", "ta=ta", "--afntool", "/bin/true"],
                         capture_output=True, text=True)
    assert res.returncode != 0
    assert "eval_history ERROR: no frame.NNNN.exr" in res.stderr


def test_strip_puts_labelled_columns_side_by_side(tmp_path):
    oiio = pytest.importorskip("OpenImageIO")
    for name, value in (("a", 0.2), ("b", 0.8)):
        for f in (3, 4):
            buf = oiio.ImageBuf(oiio.ImageSpec(16, 8, 3, "float"))
            oiio.ImageBufAlgo.fill(buf, (value, value, value))
            assert buf.write(str(tmp_path / ("%s.%04d.exr" % (name, f))))
    out = tmp_path / "strip.png"
    subprocess.run([sys.executable, os.path.join(HERE, "..", "strip.py"), str(out),
                    "--frames", "3,4", "--scale", "2",
                    "A=%s" % (tmp_path / "a.####.exr"), "B=%s" % (tmp_path / "b.####.exr")],
                   check=True)
    img = oiio.ImageBuf(str(out))
    spec = img.spec()
    assert (spec.width, spec.height) == (2 * 32, 18 + 2 * 16)
    left = img.getpixel(10, 18 + 20)
    right = img.getpixel(32 + 10, 18 + 20)
    assert right[0] > left[0]  # column B is the brighter sequence, after the sRGB transform
