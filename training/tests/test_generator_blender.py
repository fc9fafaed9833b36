# SPDX-License-Identifier: Apache-2.0
"""Blender tests of the scene generator: every family builds and renders, and the driver writes
sample counts, unblurred vectors, averaged references and resumes (skipped without Blender)."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TRAINING, "scenes"))
sys.path.insert(0, TRAINING)
import dataset_exr  # noqa: E402
import reference_noise  # noqa: E402
from generator import split  # noqa: E402
from generator.describe import describe  # noqa: E402
from generator.families import FAMILIES  # noqa: E402

pytestmark = pytest.mark.skipif(shutil.which("blender") is None, reason="Blender not installed")


def test_every_family_builds_and_renders_a_tiny_frame(tmp_path):
    listing = tmp_path / "descriptions.json"
    listing.write_text(json.dumps([describe(f, 0, 2) for f in FAMILIES]))
    script = os.path.join(TRAINING, "tests", "blender_build_families.py")
    run = subprocess.run(["blender", "-b", "--factory-startup", "-t", "2", "--python-exit-code",
                          "1", "--python", script, "--", str(listing), str(tmp_path)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    built = [line.split() for line in run.stdout.splitlines() if line.startswith("built ")]
    assert [b[1] for b in built] == list(FAMILIES)
    for _, family, meshes, lights in built:
        assert int(meshes) >= 5, family
        assert (tmp_path / (family + ".exr")).exists()
        assert dataset_exr.samples(str(tmp_path / (family + ".exr"))) == 1


def _blurred_eval_scene():
    for k in range(50):
        family, seed = split.HELD_OUT_FAMILIES[0], split.EVAL_SEED_START + k
        if describe(family, seed, 2)["motion_blur"]:
            return family, seed
    raise AssertionError("no motion-blurred held-out scene in 50 seeds")


def test_driver_writes_levels_headers_vectors_references_and_resumes(tmp_path):
    family, seed = _blurred_eval_scene()
    cmd = [sys.executable, os.path.join(TRAINING, "generate-dataset"), "--out", str(tmp_path),
           "--sequences", "%s:%d,tabletop:1" % (family, seed), "--frames", "2", "--height", "18",
           "--eval-frames", "2", "--eval-levels", "1,4", "--eval-ref-spp", "4",
           "--eval-ref-parts", "2", "--levels", "1,2,4", "--extra-spp", "3"]
    first = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert first.returncode == 0, first.stdout[-3000:] + first.stderr[-3000:]
    name = split.sequence_name(family, seed)
    seq = tmp_path / "eval" / name
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    rec = manifest["sequences"][name]
    assert rec["split"] == "eval" and rec["complete"] and rec["motion_blur"]
    assert json.loads((seq / "description.json").read_text()) == describe(family, seed, 2)
    for level in (1, 4):
        for f in (0, 1):
            frame = str(seq / ("spp%d" % level) / ("frame.%04d.exr" % f))
            assert dataset_exr.samples(frame) == level
            spec, pix = dataset_exr.read(frame)
            assert spec.getattribute(dataset_exr.VECTOR_SOURCE_ATTR)
            vspec, vpix = dataset_exr.read(str(seq / ("vector.%04d.exr" % f)))
            mine = dataset_exr.vector_channels(list(spec.channelnames))
            theirs = dataset_exr.vector_channels(list(vspec.channelnames))
            assert np.array_equal(pix[..., mine], vpix[..., theirs])
            assert np.abs(pix[..., mine]).max() > 0  # the blurred render alone had zeros
            assert os.path.realpath(seq / ("spp%d" % level) / ("reference.%04d.exr" % f)) == \
                os.path.realpath(seq / ("reference.%04d.exr" % f))
    ref = str(seq / "reference.0000.exr")
    assert dataset_exr.samples(ref) == 4
    assert dataset_exr.header(ref).getattribute(dataset_exr.PARTS_ATTR)
    _, a = dataset_exr.read(str(seq / "reference_part0.0000.exr"))
    _, b = dataset_exr.read(str(seq / "reference_part1.0000.exr"))
    _, r = dataset_exr.read(ref)
    assert np.allclose(r, (a + b) / 2, atol=1e-6) and not np.array_equal(a, b)
    rows = reference_noise.parts_noise(str(tmp_path))
    assert [row["frame"] for row in rows] == [0, 1]
    for row in rows:  # two parts: the average is 6.02 dB cleaner than part 0 vs part 1
        assert abs(row["reference_psnr_db"] - row["part_vs_part_psnr_db"] - 6.02) < 0.011
        assert set(row) >= {"input_1spp_psnr_db", "input_4spp_psnr_db"}

    # Training: each level's reference is the sample-weighted mean of the other levels and extra.
    train = tmp_path / "train" / "tabletop-0000001"
    assert manifest["sequences"]["tabletop-0000001"]["reference_samples"] == \
        {"spp1": 9, "spp2": 8, "spp4": 6}
    frames = {n: dataset_exr.read(str(train / ("spp%d" % n) / "frame.0001.exr")) for n in (1, 2, 4)}
    extra = dataset_exr.read(str(train / "extra.0001.exr"))
    rgba = lambda sp: sp[1][..., dataset_exr.combined_channels(list(sp[0].channelnames))]  # noqa
    target = str(train / "spp2" / "reference.0001.exr")
    assert dataset_exr.samples(target) == 8 and not os.path.islink(target)
    expected = (rgba(frames[1]) * 1 + rgba(frames[4]) * 4 + rgba(extra) * 3) / 8
    assert np.allclose(rgba(dataset_exr.read(target)), expected, rtol=1e-5, atol=1e-6)

    second = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert second.returncode == 0, second.stderr
    assert "wrote" not in second.stdout
