# SPDX-License-Identifier: Apache-2.0
"""The temporal term of the training loss: frame pairs share their crop and
augmentation, and the term measures flicker, not the image error."""

import os
import sys

import numpy as np
import torch

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TRAINING)
from afn import dataset, loss  # noqa: E402


def _scene(frames=4, h=20, w=24):
    rng = np.random.RandomState(3)
    s = {k: rng.rand(frames, h, w, 1 if k == "depth01" else 3).astype(np.float32)
         for k in dataset.KEYS}
    # frame index written into every pixel of c1's first channel: shows which frame a crop is from
    s["c1"][..., 0] = np.arange(frames, dtype=np.float32)[:, None, None] + 10.0
    return s


def test_pairs_are_consecutive_frames_with_one_window_and_augmentation():
    s = _scene()
    sampler = dataset.CropSampler([s], crop=8, seed=0)
    for _ in range(20):
        prev, cur = sampler.sample_pair()
        fp = np.unique(prev["c1"][..., 0])
        fc = np.unique(cur["c1"][..., 0])
        assert len(fp) == 1 and len(fc) == 1
        # (f + 10) * gain and (f + 9) * gain: consecutive frames, one brightness jitter
        f = [g for g in range(1, 4) if np.isclose(fc[0] / fp[0], (g + 10) / (g + 9), rtol=1e-6)]
        assert len(f) == 1
        f = f[0]
        gain = fc[0] / (f + 10)
        assert 0.8 <= gain <= 1.2
        # the same window and flips in both frames (albedo is not jittered)
        window = [np.array_equal(cur["albedo"], a) for a in _windows(s["albedo"][f], 8, flips=True)]
        assert any(window)
        fwin = window.index(True)
        assert np.array_equal(prev["albedo"], _windows(s["albedo"][f - 1], 8, flips=True)[fwin])


def _windows(img, c, flips):
    out = []
    for y in range(img.shape[0] - c + 1):
        for x in range(img.shape[1] - c + 1):
            a = img[y:y + c, x:x + c]
            for fx in (False, True):
                for fy in (False, True):
                    b = a[:, ::-1] if fx else a
                    out.append(b[::-1] if fy else b)
    return out


def test_pair_batch_puts_current_frames_first():
    sampler = dataset.CropSampler([_scene()], crop=8, seed=1)
    b = sampler.pair_batch(3)
    assert b["c1"].shape == (6, 8, 8, 3)
    for i in range(3):
        assert b["c1"][i, 0, 0, 0] > b["c1"][i + 3, 0, 0, 0]


def test_single_frames_are_unchanged_by_the_pair_code():
    """sample() draws the same crops as before pairs existed: resumed runs stay reproducible."""
    s = _scene()
    a = dataset.CropSampler([s], crop=8, seed=7)
    rng = np.random.RandomState(7)
    for _ in range(5):
        crop = a.sample()
        rng.randint(1)
        f = rng.randint(4)
        y, x = rng.randint(20 - 8 + 1), rng.randint(24 - 8 + 1)
        fx, fy, gain = rng.rand() < 0.5, rng.rand() < 0.5, np.float32(rng.uniform(0.8, 1.2))
        want = s["c1"][f, y:y + 8, x:x + 8]
        want = want[:, ::-1] if fx else want
        want = want[::-1] if fy else want
        np.testing.assert_array_equal(crop["c1"], want * gain)


def test_temporal_term_sees_flicker_not_a_steady_error():
    t = torch.rand(4, 3, 8, 8)                      # 2 current frames, then their 2 previous
    assert loss.temporal_gradient(t, t).item() == 0.0
    # wrong, but wrong the same way in both frames of each pair: no flicker, no temporal term
    target = torch.cat([t[:2], t[:2]])
    steady = torch.cat([t[:2] * 0.5, t[:2] * 0.5])
    assert loss.smape(steady, target).item() > 0.1
    assert loss.temporal_gradient(steady, target).item() == 0.0
    flicker = t.clone()
    flicker[:2] += 0.2                              # current frames jump, previous ones do not
    assert loss.temporal_gradient(flicker, t).item() > 0.05


def test_training_with_the_temporal_term_runs_and_learns_finite_weights(tmp_path):
    import pytest
    pytest.importorskip("OpenImageIO")
    from afn import train
    from afn.weights import load_model
    seq = os.path.join(TRAINING, "..", "examples", "sequence")
    if not os.path.exists(os.path.join(seq, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    out = str(tmp_path / "run")
    train.main(["--data", seq, "--out", out, "--steps", "2", "--batch", "4", "--crop", "32",
                "--max-frames", "3", "--enc", "4,4,4", "--dec", "4,4", "--refine", "4",
                "--device", "cpu", "--epochs", "1", "--temporal-weight", "0.5"])
    line = open(os.path.join(out, "log.csv")).read().splitlines()[1].split(",")
    assert line[0] == "1" and np.isfinite(float(line[1]))     # train SMAPE (no validation here)
    model = load_model(os.path.join(out, "model.afnw"))
    assert all(torch.isfinite(p).all() for p in model.parameters())
