# SPDX-License-Identifier: Apache-2.0
"""The data pipeline and the training/export scripts on the committed example sequence (smoke:
two frames, 32x32 crops, one tiny epoch; checks the code path, not the learning)."""

import os
import sys

import numpy as np
import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEQUENCE = os.path.join(TRAINING, "..", "examples", "sequence")
sys.path.insert(0, TRAINING)

pytest.importorskip("OpenImageIO")
from afn import dataset, export, train  # noqa: E402
from afn.weights import load_model  # noqa: E402


@pytest.fixture(scope="module")
def scene():
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    return dataset.load_scene(SEQUENCE, max_frames=2)


def test_load_scene_prepares_inputs(scene):
    f, h, w, _ = scene["c1"].shape
    assert f == 2 and (h, w) == (180, 320)
    assert scene["depth01"].shape == (2, h, w, 1)
    for k in dataset.KEYS:
        assert np.isfinite(scene[k]).all(), k
    assert scene["albedo"].min() >= 0 and scene["albedo"].max() <= 1
    assert scene["normal01"].min() >= 0 and scene["normal01"].max() <= 1
    assert scene["depth01"].min() == 0 and scene["depth01"].max() == 1
    assert np.array_equal(scene["cta"][0], scene["c1"][0])    # first frame: no history
    assert not np.array_equal(scene["cta"][1], scene["c1"][1])
    # history01 = 1 / frames accumulated: 1 on the first frame, 1/2 where frame 1 kept its history
    assert np.all(scene["history01"][0] == 1.0)
    assert 0.5 < np.mean(scene["history01"][1] == 0.5) < 1.0   # disocclusions and the sky reset


def _passes():
    px = dataset.read_layers(os.path.join(SEQUENCE, "frame.0000.exr"), {
        "color": ("ViewLayer.Combined", "RGB"), "albedo": ("ViewLayer.Denoising Albedo", "RGB")})
    color = np.where(np.isfinite(px["color"]), np.maximum(px["color"], 0), 0).astype(np.float32)
    albedo = np.clip(np.nan_to_num(px["albedo"]), 0, 1).astype(np.float32)
    return color, albedo


def _demodulate(color, albedo):
    return np.minimum(color / np.maximum(albedo, np.float32(2.0 ** -10)), np.float32(1e15))


def test_features_are_the_cores_inputs(scene):
    """c1 is the 1-spp colour over max(d, 2^-10) exactly as the core computes it (float32), d being
    the "albedo" feature (the demodulation factor that training remodulates with), read from the
    Blender passes here only to cross-check afntool --features. The example's Denoising Albedo is
    noisy on the gold torus, so aux=auto prefilters it there and leaves the rest as given."""
    color, albedo = _passes()
    np.testing.assert_array_equal(scene["c1"][0], _demodulate(color, scene["albedo"][0]))
    same = np.all(scene["albedo"][0] == albedo, axis=2)
    assert 0.9 < same.mean() < 1.0


def test_clean_aux_features_use_the_albedo_as_given():
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    clean = dataset.load_scene(SEQUENCE, max_frames=1, aux="clean")
    color, albedo = _passes()
    np.testing.assert_array_equal(clean["c1"][0], _demodulate(color, albedo))
    np.testing.assert_array_equal(clean["albedo"][0], albedo)


def test_a_missing_afntool_is_a_clear_error(monkeypatch, tmp_path):
    from afn import afntool
    monkeypatch.setenv("AFNTOOL", str(tmp_path / "no-such-afntool"))
    with pytest.raises(afntool.AfntoolError, match="afntool not found"):
        dataset.load_scene(SEQUENCE, max_frames=1)


def test_crop_sampler(scene):
    s = dataset.CropSampler([scene], crop=40, seed=1)
    b = s.batch(3)
    assert b["c1"].shape == (3, 40, 40, 3) and b["depth01"].shape == (3, 40, 40, 1)
    big = dataset.CropSampler([scene], crop=256, seed=1).sample()   # taller than the frame: padded
    assert big["c1"].shape == (256, 256, 3)


def _tiny_run(out):
    """afn.train arguments of a tiny smoke run on two frames of the example sequence into out."""
    return ["--data", SEQUENCE, "--out", out, "--steps", "1", "--batch", "2", "--crop", "32",
            "--max-frames", "2", "--enc", "4,4,4", "--dec", "4,4", "--refine", "4",
            "--device", "cpu"]


def test_history_input_and_albedo_trust_train_export_and_run_in_the_core(tmp_path):
    """A model with the history input and the learned albedo trust trains on the features'
    history01, exports with history=1 and albedoTrust=1, and the C++ core runs it (afntool
    --weights) on the example."""
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    out = str(tmp_path / "run")
    train.main(_tiny_run(out) + ["--epochs", "1", "--history", "--albedo-trust"])
    export.main([out, "-o", str(tmp_path / "h.afnw")])
    model = load_model(str(tmp_path / "h.afnw"))
    assert model.cfg.history and model.enc1.weight.shape[1] == 14
    assert model.cfg.albedo_trust and model.headG.weight.shape[1] == model.cfg.enc[0]
    from afn import afntool
    afntool.run(["-q", "--frames", "0-1", os.path.join(SEQUENCE, "frame.####.exr"),
                 "--denoise:method=afn:weights=" + str(tmp_path / "h.afnw"),
                 "-o", str(tmp_path / "o.####.exr")])
    assert os.path.exists(str(tmp_path / "o.0001.exr"))


def test_train_resume_and_export(tmp_path):
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    out = str(tmp_path / "run")
    common = _tiny_run(out)
    train.main(common + ["--epochs", "1"])
    train.main(common + ["--epochs", "2"])                  # resumes at epoch 1
    lines = open(os.path.join(out, "log.csv")).read().splitlines()
    assert lines[0].startswith("epoch,") and [ln.split(",")[0] for ln in lines[1:]] == ["1", "2"]
    export.main([out, "-o", str(tmp_path / "m.afnw")])
    model = load_model(str(tmp_path / "m.afnw"))
    assert model.cfg.enc == (4, 4, 4)


def test_time_limit_and_init(tmp_path):
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    tiny = ["--data", SEQUENCE, "--steps", "1", "--batch", "2", "--crop", "32", "--max-frames", "2",
            "--enc", "4,4,4", "--dec", "4,4", "--refine", "4", "--device", "cpu"]
    first = str(tmp_path / "first")
    # A limit already passed after the first epoch: exactly one epoch of the 50 asked for runs.
    train.main(tiny + ["--out", first, "--epochs", "50", "--minutes", "1e-9"])
    assert len(open(os.path.join(first, "log.csv")).read().splitlines()) == 2
    # --init starts a new run from those weights (here the checkpoint; .afnw below).
    start = load_model(os.path.join(first, "model.afnw"))
    fresh = str(tmp_path / "fresh")
    train.main(tiny + ["--out", fresh, "--epochs", "1", "--seed", "5", "--init",
                       os.path.join(first, "checkpoints", "latest.pt")])
    tuned = load_model(os.path.join(fresh, "model.afnw"))
    a, b = start.state_dict(), tuned.state_dict()
    assert a.keys() == b.keys()
    # One Adam step at lr 1e-3 moves every weight by at most ~1e-3 from where it started.
    assert max((a[k] - b[k]).abs().max().item() for k in a) < 5e-3
    with pytest.raises(RuntimeError):  # another architecture is refused
        train.main(tiny[:-6] + ["--enc", "8,8,8", "--dec", "4,4", "--refine", "4", "--device", "cpu",
                                "--out", str(tmp_path / "bad"), "--epochs", "1", "--init",
                                os.path.join(first, "model.afnw")])


def test_init_across_ablation_variants(tmp_path):
    import torch
    from afn.model import AFN, AFNConfig
    small = dict(enc=(4, 4, 4), dec=(4, 4), refine=4)
    full = AFN(AFNConfig(variant="full", **small))
    fusion = AFN(AFNConfig(variant="fusion", **small))
    train.init_weights(fusion, _save(full, tmp_path / "full.afnw"), "cpu")
    for k, v in fusion.state_dict().items():        # every fusion tensor comes from the full model
        assert torch.equal(v, full.state_dict()[k]), k
    back = AFN(AFNConfig(variant="full", **small))
    before = {k: v.clone() for k, v in back.state_dict().items()}
    train.init_weights(back, _save(fusion, tmp_path / "fusion.afnw"), "cpu")
    for k, v in back.state_dict().items():          # refinement keeps its own initialisation
        src = fusion.state_dict().get(k)
        assert torch.equal(v, src if src is not None else before[k]), k
    assert any(k not in fusion.state_dict() for k in back.state_dict())
    wide = AFN(AFNConfig(variant="full", enc=(8, 4, 4), dec=(4, 4), refine=4))
    with pytest.raises(RuntimeError, match="shape"):
        train.init_weights(wide, str(tmp_path / "full.afnw"), "cpu")


def _save(model, path):
    from afn.weights import save_model
    save_model(str(path), model)
    return str(path)


def test_cosine_learning_rate_schedule(tmp_path):
    args = train.parse_args(["--data", "x", "--out", "y", "--epochs", "5", "--lr", "4e-4",
                             "--lr-end", "1e-5"])
    rates = [train.epoch_lr(args, e) for e in range(5)]
    assert rates[0] == pytest.approx(4e-4) and rates[-1] == pytest.approx(1e-5)
    assert rates[2] == pytest.approx(0.5 * (4e-4 + 1e-5))           # the cosine's midpoint
    assert all(a > b for a, b in zip(rates, rates[1:]))               # falls every epoch
    constant = train.parse_args(["--data", "x", "--out", "y", "--epochs", "5", "--lr", "4e-4"])
    assert [train.epoch_lr(constant, e) for e in range(5)] == [4e-4] * 5
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        return
    # A resumed run continues the schedule: the optimizer runs at the rate of its epoch.
    out = str(tmp_path / "run")
    common = _tiny_run(out) + ["--epochs", "3", "--lr", "1e-3", "--lr-end", "1e-4"]
    train.main(common + ["--minutes", "1e-9"])                       # epoch 1 only
    train.main(common)                                               # resumes: epochs 2, 3
    import torch
    ck = torch.load(os.path.join(out, "checkpoints", "latest.pt"))
    assert ck["epoch"] == 3
    assert ck["optimizer"]["param_groups"][0]["lr"] == pytest.approx(1e-4)


def test_keep_epochs_keeps_the_last_n_and_they_average(tmp_path):
    if not os.path.exists(os.path.join(SEQUENCE, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    import torch
    from afn import average
    out = str(tmp_path / "run")
    common = _tiny_run(out) + ["--keep-epochs", "2", "--epochs"]
    train.main(common + ["2"])
    train.main(common + ["3"])                                       # resumed: epoch 3
    epochs = os.path.join(out, "epochs")
    assert sorted(os.listdir(epochs)) == ["E0002.afnw", "E0003.afnw"]
    last = load_model(os.path.join(epochs, "E0003.afnw")).state_dict()
    assert all(torch.equal(v, load_model(os.path.join(out, "model.afnw")).state_dict()[k])
               for k, v in last.items())
    prev = load_model(os.path.join(epochs, "E0002.afnw")).state_dict()
    assert any(not torch.equal(prev[k], last[k]) for k in last)      # two different epochs kept
    average.main([os.path.join(epochs, "E0002.afnw"), os.path.join(epochs, "E0003.afnw"),
                  "-o", str(tmp_path / "avg.afnw")])
    avg = load_model(str(tmp_path / "avg.afnw")).state_dict()
    for k in last:
        if last[k].is_floating_point():
            assert torch.allclose(avg[k], 0.5 * (prev[k] + last[k]), atol=1e-6), k
