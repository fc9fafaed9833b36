# SPDX-License-Identifier: Apache-2.0
"""The training toolkit on a generated dataset (afn-dataset-2): a tiny fake one built from the
example sequence, with the generator's layout, leave-one-out targets and an evaluation split."""

import json
import os
import shutil
import sys

import numpy as np
import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEQUENCE = os.path.join(TRAINING, "..", "examples", "sequence")
sys.path.insert(0, TRAINING)

pytest.importorskip("OpenImageIO")
import dataset_exr  # noqa: E402
from afn import afntool, dataset, generated, train  # noqa: E402

FRAMES = 2
W, H = 96, 64  # the example's top-left corner: small enough for a quick afntool


def _crop(src, dst):
    import OpenImageIO as oiio
    buf = oiio.ImageBufAlgo.cut(oiio.ImageBuf(src), oiio.ROI(0, W, 0, H))
    assert buf.write(dst), buf.geterror()


def _level(dst, src, targets):
    """A level folder: FRAMES cropped example frames and the given reference per frame."""
    os.makedirs(dst)
    for f in range(FRAMES):
        name = f"frame.{f:04d}.exr"
        shutil.copy(os.path.join(src, name), os.path.join(dst, name))
        targets(f, os.path.join(dst, f"reference.{f:04d}.exr"))


def _record(split, name, levels, complete=True):
    return {"split": split, "dir": f"{split}/{name}", "levels": levels, "complete": complete}


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    if not afntool.find_afntool():
        pytest.skip("afntool not built")
    src = str(tmp_path_factory.mktemp("cropped"))
    for f in range(FRAMES):
        for kind in ("frame", "reference"):
            name = f"{kind}.{f:04d}.exr"
            _crop(os.path.join(SEQUENCE, name), os.path.join(src, name))
    root = tmp_path_factory.mktemp("afn-v2")
    ref = lambda f: os.path.join(src, f"reference.{f:04d}.exr")  # noqa: E731
    for name in ("room-0000000", "tabletop-0000000"):
        seq = root / "train" / name
        # spp4's target is the clean reference; spp1's the leave-one-out mean of spp4 and it.
        _level(str(seq / "spp4"), src, lambda f, p: shutil.copy(ref(f), p))
        _level(str(seq / "spp1"), src, lambda f, p, seq=seq: dataset_exr.sample_weighted_mean(
            [str(seq / "spp4" / f"frame.{f:04d}.exr"), ref(f)], p, "leave-one-out (test)"))
    ev = root / "eval" / "atrium-1000000"
    for f in range(FRAMES):
        os.makedirs(ev, exist_ok=True)
        shutil.copy(ref(f), ev / f"reference.{f:04d}.exr")
    _level(str(ev / "spp1"), src,
           lambda f, p: os.symlink(os.path.join("..", f"reference.{f:04d}.exr"), p))
    os.makedirs(root / "train" / "night-0000000" / "spp1")  # still rendering: not in the manifest
    manifest = {"format": generated.FORMAT, "levels": "1,4", "eval_levels": "1", "sequences": {
        "room-0000000": _record("train", "room-0000000", [1, 4]),
        "tabletop-0000000": _record("train", "tabletop-0000000", [1, 4]),
        "atrium-1000000": _record("eval", "atrium-1000000", [1]),
        "night-0000000": _record("train", "night-0000000", [1, 4], complete=False)}}
    (root / "manifest.json").write_text(json.dumps(manifest))
    return str(root)


def test_levels_are_chosen_per_sample_count(data):
    with pytest.raises(ValueError, match="--spp"):
        dataset.find_scenes(data)
    with pytest.raises(ValueError, match="no level 64"):
        dataset.find_scenes(data, "64")
    one = dataset.find_scenes(data, "1")
    assert list(one) == ["atrium-1000000/spp1", "room-0000000/spp1", "tabletop-0000000/spp1"]
    assert one["room-0000000/spp1"] == os.path.join(data, "train", "room-0000000", "spp1")
    assert list(dataset.find_scenes(data, 4)) == ["room-0000000/spp4", "tabletop-0000000/spp4"]
    assert len(dataset.find_scenes(data, [1, 4])) == 5
    assert dataset.evaluation_scenes(data, "1,4") == {"atrium-1000000/spp1"}


def test_names_expand_to_every_selected_level(data):
    scenes = dataset.find_scenes(data, "1,4")
    assert generated.expand(["room-0000000"], scenes) == ["room-0000000/spp1", "room-0000000/spp4"]
    assert generated.expand(["room-0000000/spp4"], scenes) == ["room-0000000/spp4"]
    with pytest.raises(KeyError):
        generated.expand(["room-00000"], scenes)  # a prefix of a name is not a name


def test_flat_datasets_refuse_another_sample_count(tmp_path):
    (tmp_path / "manifest.json").write_text(json.dumps({"spp": 1}))
    assert dataset.find_scenes(str(tmp_path), "1") == {}
    with pytest.raises(ValueError, match="1-spp inputs only"):
        dataset.find_scenes(str(tmp_path), "16")


def test_leave_one_out_targets_load_through_afntool(data):
    folder = dataset.find_scenes(data, "1")["room-0000000/spp1"]
    scene = dataset.load_scene(folder)
    assert scene["c1"].shape == (FRAMES, H, W, 3)
    target = dataset.read_layers(os.path.join(folder, "reference.0001.exr"),
                                 {"t": ("ViewLayer.Combined", "RGB")})["t"]
    np.testing.assert_array_equal(scene["target"][1], target)
    assert dataset_exr.samples(os.path.join(folder, "reference.0001.exr")) == 2049  # 1 + 2048
    linked = dataset.load_scene(dataset.find_scenes(data, "1")["atrium-1000000/spp1"])
    clean = dataset.read_layers(os.path.join(data, "eval", "atrium-1000000", "reference.0000.exr"),
                                {"t": ("ViewLayer.Combined", "RGB")})["t"]
    np.testing.assert_array_equal(linked["target"][0], clean)  # through the symlink


def test_train_selects_a_level_and_never_trains_on_evaluation_scenes(data, tmp_path):
    out = str(tmp_path / "run")
    tiny = ["--data", data, "--steps", "1", "--batch", "2", "--crop", "32", "--enc", "4,4,4",
            "--dec", "4,4", "--refine", "4", "--device", "cpu", "--epochs", "1"]
    train.main(tiny + ["--out", out, "--spp", "4", "--holdout", "tabletop-0000000"])
    cfg = json.load(open(os.path.join(out, "config.json")))
    assert cfg["train_scenes"] == ["room-0000000/spp4"]
    assert cfg["holdout_scenes"] == ["tabletop-0000000/spp4"] and cfg["spp"] == "4"
    with pytest.raises(SystemExit, match="evaluation scenes"):
        train.main(tiny + ["--out", str(tmp_path / "bad"), "--spp", "1", "--scenes",
                           "atrium-1000000"])
    with pytest.raises(SystemExit, match="choose levels with --spp"):
        train.main(tiny + ["--out", str(tmp_path / "bad")])
    with pytest.raises(SystemExit, match="not in"):
        train.main(tiny + ["--out", str(tmp_path / "bad"), "--spp", "1", "--holdout", "castle-1"])
