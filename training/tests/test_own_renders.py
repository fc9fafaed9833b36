# SPDX-License-Identifier: Apache-2.0
"""Training on one's own renders: other renderers' pass names through the C++ core's role mapping
(or a clear error listing the file's channels, never a traceback), docs that match the tree, and
a training protocol that never writes the shipped weights."""

import hashlib
import os
import re
import subprocess
import sys

import numpy as np
import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO = os.path.dirname(TRAINING)
sys.path.insert(0, TRAINING)

oiio = pytest.importorskip("OpenImageIO")
from afn import afntool, dataset  # noqa: E402

W, H = 24, 16


def write_exr(path, channels, pixels, attrs=None):
    spec = oiio.ImageSpec(W, H, len(channels), "float")
    spec.channelnames = tuple(channels)
    for k, v in (attrs or {}).items():
        spec.attribute(k, v)
    out = oiio.ImageOutput.create(path)
    assert out.open(path, spec), oiio.geterror()
    out.write_image(np.ascontiguousarray(pixels, np.float32))
    out.close()


def make_scene(folder, channels, attrs=None, frames=2):
    """frame.NNNN.exr and reference.NNNN.exr with the given channels (random values in [0, 1])."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.RandomState(1)
    for f in range(frames):
        for stem in ("frame", "reference"):
            px = rng.rand(H, W, len(channels)).astype(np.float32)
            write_exr(os.path.join(folder, f"{stem}.{f:04d}.exr"), channels, px, attrs)
    return folder


ARNOLD = ["R", "G", "B", "A", "diffuse_albedo.R", "diffuse_albedo.G", "diffuse_albedo.B",
          "N.R", "N.G", "N.B", "Z", "P.R", "P.G", "P.B", "motionvector.R", "motionvector.G"]
UNMAPPED = ["diffuse.R", "diffuse.G", "diffuse.B", "N.X", "N.Y", "N.Z"]


@pytest.fixture(scope="module")
def tool():
    path = afntool.find_afntool()
    if not path:
        pytest.skip("afntool not built")
    return path


def test_arnold_named_folder_loads(tmp_path, tool):
    scene = make_scene(str(tmp_path / "shot"), ARNOLD, {"arnold/version": "7.2"})
    s = dataset.load_scene(scene, tool=tool)
    assert s["c1"].shape == (2, H, W, 3) and s["depth01"].shape == (2, H, W, 1)
    # The file's albedo (0..1 random) reached the features: not the 1 used when there is none.
    assert s["albedo"].min() < 0.5


def test_unmapped_passes_give_a_clear_error_with_the_channels(tmp_path, tool):
    scene = make_scene(str(tmp_path / "shot"), UNMAPPED)
    with pytest.raises(dataset.SceneError) as err:
        dataset.load_scene(scene, tool=tool)
    msg = str(err.value)
    for ch in UNMAPPED:
        assert ch in msg, msg
    assert "--aov" in msg


def test_aov_overrides_reach_the_core(tmp_path, tool):
    scene = make_scene(str(tmp_path / "shot"), UNMAPPED)
    s = dataset.load_scene(scene, tool=tool, aov=["color=diffuse.R,diffuse.G,diffuse.B"])
    assert s["c1"].shape == (2, H, W, 3)


def test_train_cli_reports_bad_folders_without_a_traceback(tmp_path, tool):
    bad = make_scene(str(tmp_path / "data" / "shot"), UNMAPPED)
    env = dict(os.environ, AFNTOOL=tool)
    args = [sys.executable, "-m", "afn.train", "-d", os.path.dirname(bad), "-o",
            str(tmp_path / "out"), "-e", "1", "--steps", "1", "-b", "1", "--crop", "8",
            "--enc", "4,4,4", "--dec", "4,4", "--refine", "4", "--threads", "1"]
    p = subprocess.run(args, cwd=TRAINING, env=env, capture_output=True, text=True)
    assert p.returncode != 0
    assert "Traceback" not in p.stderr, p.stderr
    assert "diffuse.R" in p.stderr and "--aov" in p.stderr, p.stderr
    # Files under other names: the expected layout is named.
    empty = tmp_path / "renders" / "shot"
    empty.mkdir(parents=True)
    (empty / "beauty.0001.exr").write_bytes(b"")
    args[4] = str(tmp_path / "renders")
    p = subprocess.run(args, cwd=TRAINING, env=env, capture_output=True, text=True)
    assert p.returncode != 0 and "Traceback" not in p.stderr, p.stderr
    assert "frame.NNNN.exr" in p.stderr and "reference.NNNN.exr" in p.stderr, p.stderr


def _sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def test_train_default_never_writes_the_shipped_weights(tmp_path):
    script = os.path.join(TRAINING, "train-default.sh")
    # Static: no command of the script writes into the source tree's weights/ or docs/.
    text = open(script).read()
    for target in re.findall(r"(?:-o|--out|--json)\s+(\S+)", text):
        assert "weights/" not in target and "docs/" not in target, target
    # Dry run: every command printed, none run; the export goes to RESULTS, the install is shown.
    weights = os.path.join(REPO, "weights", "afn.afnw")
    before = _sha(weights) if os.path.exists(weights) else None
    out = tmp_path / "results"
    p = subprocess.run(["bash", script, str(tmp_path / "data"), str(out)],
                       env=dict(os.environ, AFN_DRY_RUN="1"), capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert f"-o {out}/ship/afn.afnw" in p.stdout, p.stdout
    assert "cp " in p.stdout and "weights/afn.afnw" in p.stdout
    assert not out.exists(), "a dry run creates nothing"
    assert (_sha(weights) if os.path.exists(weights) else None) == before


def test_readme_names_only_paths_of_a_clone():
    """Every path training/README.md names exists in the repository, except what its commands
    make (results/, build/, data/ and placeholders)."""
    text = open(os.path.join(TRAINING, "README.md")).read()
    assert "/work/" not in text, "a path of one machine"
    made = ("results/", "OUT/", "RESULTS/", "build/", "../data/", "data/", "../build/")
    # Scene names inside a generated dataset (FAMILY-SEED/sppS) are not paths of the tree.
    scene_names = re.compile(r"^[a-z_]+-\d+/spp\d+$")
    missing = []
    for token in re.findall(r"`([^`\s]+)`", text):
        if ("/" not in token or token.startswith(made) or re.search(r"[<>*#]|NNNN", token)
                or scene_names.match(token)):
            continue
        path = token.split(":")[0].rstrip(",.")
        if not any(os.path.exists(os.path.join(base, path)) for base in (TRAINING, REPO)):
            missing.append(token)
    assert not missing, missing
