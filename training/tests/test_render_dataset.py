# SPDX-License-Identifier: Apache-2.0
"""Tests of the dataset driver (training/render_dataset.py) and the scene library's metadata."""

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio
import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TRAINING)
import render_dataset as rd  # noqa: E402

# What the scene library must cover between its scenes.
REQUIRED_COVERAGE = {
    "glossy", "mirror", "soft_shadows", "hard_shadows", "moving_light_static_camera",
    "light_switch", "fine_geometry", "high_frequency_texture", "refraction", "emissive", "indoor",
    "outdoor_sky", "slow_camera", "fast_camera", "moving_objects",
}


def test_library_has_eight_scenes_covering_the_issue():
    scenes = rd.list_scenes()
    assert len(scenes) >= 8
    covered = set().union(*(set(info["covers"]) for info in scenes.values()))
    assert REQUIRED_COVERAGE - covered == set()
    for info in scenes.values():
        assert info["description"] and isinstance(info["defaults"], dict)


def test_scene_info_names_the_file_when_metadata_is_missing(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("DESCRIPTION = 'x'\n")
    with pytest.raises(rd.DatasetError, match="COVERS.*bad.py"):
        rd.scene_info(str(bad))


def test_width_is_16_by_9_and_even():
    assert rd.width_for(72) == 128
    assert rd.width_for(180) == 320
    assert rd.width_for(36) == 64
    assert rd.width_for(25) % 2 == 0


def test_scene_seed_depends_on_name_and_seed_only():
    assert rd.scene_seed("glass", 0) == rd.scene_seed("glass", 0)
    assert rd.scene_seed("glass", 0) != rd.scene_seed("neon", 0)
    assert rd.scene_seed("glass", 1) != rd.scene_seed("glass", 0)


def test_resume_refuses_other_settings(tmp_path):
    (tmp_path / "scene.json").write_text(json.dumps({"frames": 4, "height": 72}))
    rd.check_resume(str(tmp_path), {"frames": 4, "height": 72})
    with pytest.raises(rd.DatasetError, match="height=72"):
        rd.check_resume(str(tmp_path), {"frames": 4, "height": 90})


def test_unknown_scene_is_a_clear_error(tmp_path):
    with pytest.raises(rd.DatasetError, match="unknown scene.*nosuch"):
        rd.main(["--out", str(tmp_path), "--scenes", "nosuch"])


def test_list_prints_every_scene(capsys):
    assert rd.main(["--list"]) == 0
    out = capsys.readouterr().out
    for name in rd.list_scenes():
        assert name in out


def _project(camera, points, width, height):
    """Blender raster position (pixels, y up) of world ``points`` seen by a recorded camera."""
    world_to_cam = np.linalg.inv(np.array(camera["matrix_world"]))
    pc = points @ world_to_cam[:3, :3].T + world_to_cam[:3, 3]
    focal = camera["lens_mm"] / camera["sensor_width_mm"]  # horizontal sensor fit (16:9)
    x = (0.5 + focal * pc[..., 0] / -pc[..., 2]) * width
    y = 0.5 * height + focal * width * pc[..., 1] / -pc[..., 2]
    return np.stack([x, y], -1)


def _passes(path):
    buf = oiio.ImageBuf(path)
    names = list(buf.spec().channelnames)
    pixels = buf.get_pixels(oiio.FLOAT)
    return lambda name: pixels[:, :, names.index("ViewLayer." + name)]


@pytest.mark.skipif(shutil.which("blender") is None, reason="Blender not installed")
def test_render_two_tiny_frames_resume_and_motion_vectors(tmp_path):
    cmd = [sys.executable, os.path.join(TRAINING, "render-dataset"), "--out", str(tmp_path),
           "--scenes", "fine_geometry", "--frames", "2", "--height", "18", "--ref-spp", "2"]
    first = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert first.returncode == 0, first.stderr
    scene_dir = tmp_path / "fine_geometry"
    for name in ("frame.0000.exr", "frame.0001.exr", "reference.0001.exr", "scene.json"):
        assert (scene_dir / name).exists()
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    rec = manifest["scenes"]["fine_geometry"]
    assert (rec["width"], rec["height"], rec["spp"], rec["ref_spp"]) == (32, 18, 1, 2)
    assert manifest["blender"]

    # Vector.XY = (where the surface was at t-1) - (where it is at t), in pixels with y up:
    # recompute it from the Position pass and the cameras recorded in scene.json.
    state = json.loads((scene_dir / "scene.json").read_text())
    chan = _passes(str(scene_dir / "frame.0001.exr"))
    points = np.stack([chan("Position.X"), chan("Position.Y"), chan("Position.Z")], -1)
    vector = np.stack([chan("Vector.X"), chan("Vector.Y")], -1)
    hit = chan("Depth.Z") < 1e9
    expected = (_project(state["cameras"]["0"], points, 32, 18)
                - _project(state["cameras"]["1"], points, 32, 18))
    assert np.abs(vector[hit]).max() > 0.5  # the camera pans fast
    assert np.median(np.abs(vector - expected)[hit]) < 1e-2

    second = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert second.returncode == 0, second.stderr
    assert "skip" in second.stdout and "wrote" not in second.stdout
