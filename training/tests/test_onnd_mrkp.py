# SPDX-License-Identifier: Apache-2.0
"""Learned baselines ONND and MR-KP: shapes, recurrence, kernel normalisation, level blending,
losses, the sequence sampler, export metadata and costs."""

import os
import sys

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from afn.baselines import mrkp, onnd  # noqa: E402
from afn.baselines.common import SequenceSampler  # noqa: E402
from afn.baselines.onnd_mrkp_train import export  # noqa: E402
from afn.weights import loads  # noqa: E402


def _inputs(h=21, w=37, b=2, seed=0):
    g = torch.Generator().manual_seed(seed)
    return (torch.rand(b, 3, h, w, generator=g) * 3, torch.rand(b, 3, h, w, generator=g),
            torch.rand(b, 3, h, w, generator=g), torch.rand(b, 1, h, w, generator=g))


def test_onnd_shapes_and_recurrence():
    torch.manual_seed(0)
    net = onnd.ONND(enc=(6, 8, 10), bottleneck=12).eval()
    x = _inputs()
    with torch.no_grad():
        a, state = net(*x)
        b, _ = net(*x, state)
        c, _ = net(*x)
    assert a.shape == (2, 3, 21, 37)
    assert [s.shape[1] for s in state] == [6, 8, 10]
    assert torch.equal(a, c)                 # no state -> deterministic frame
    assert (a - b).abs().max() > 1e-4        # the previous frame's state changes the output
    assert (a >= -1.0).all()                 # exp(.) - 1


def test_onnd_contrast_gate_is_zero_on_flat_windows_and_open_on_noise():
    for v in (0.0, 1e-3, 0.37, 3.0):
        assert onnd.contrast_gate(torch.full((1, 3, 7, 9), v)).max() == 0.0
    g = torch.Generator().manual_seed(1)
    noisy = 0.7 + 0.6 * torch.rand(1, 3, 12, 16, generator=g)
    assert onnd.contrast_gate(noisy).min() == 1.0
    step = torch.ones(1, 3, 4, 10)
    step[:, 1, :, 5:] = 1.05
    gate = onnd.contrast_gate(step)[0, 0]
    want = min(onnd.GATE_GAIN * 0.05 / (2.05 + onnd.GATE_EPS), 1.0)
    assert 0.0 < want < 1.0
    assert torch.allclose(gate[:, 4:6], torch.full((4, 2), want), rtol=1e-5)
    assert gate[:, :4].max() == 0.0 and gate[:, 6:].max() == 0.0


def test_onnd_returns_flat_frames_exactly_whatever_the_state():
    torch.manual_seed(0)
    net = onnd.ONND(enc=(6, 8, 10), bottleneck=12).eval()
    aux = [torch.full((1, c, 21, 37), 0.5) for c in (3, 3, 1)]
    with torch.no_grad():
        for v in (0.0, 1e-3, 0.37, 3.0):
            cta, state = torch.full((1, 3, 21, 37), v), None
            for _ in range(4):
                irr, state = net(cta, *aux, state)
                assert torch.equal(irr, cta)


def test_onnd_loss_is_finite_and_trains():
    torch.manual_seed(0)
    net = onnd.ONND(enc=(4, 6), bottleneck=8)
    seq = {k: torch.rand(3, 2, c, 16, 16) for k, c in
           (("cta", 3), ("albedo", 3), ("normal01", 3), ("depth01", 1), ("target", 3))}
    loss = onnd.sequence_loss(net, seq, onnd.log_kernel())
    loss.backward()
    assert torch.isfinite(loss)
    assert all(torch.isfinite(p.grad).all() for p in net.parameters())


def test_log_kernel_is_zero_mean_and_symmetric():
    k = onnd.log_kernel()[0, 0]
    assert k.shape == (9, 9)
    assert abs(float(k.sum())) < 1e-6
    assert torch.allclose(k, k.t()) and torch.allclose(k, k.flip(0))


def test_mrkp_kernels_preserve_constant_images():
    img = torch.full((1, 3, 9, 11), 2.5)
    logits = torch.randn(1, mrkp.HEAD, 9, 11) + 1.0
    out = mrkp.apply_kernel(img, logits)
    assert torch.allclose(out, img, atol=1e-5)


def test_mrkp_constant_input_gives_constant_output():
    torch.manual_seed(0)
    net = mrkp.MRKP(width=8).eval()
    cta = torch.full((1, 3, 21, 37), 0.7)
    _, alb, nrm, dep = _inputs(b=1)
    with torch.no_grad():
        out = net(cta, alb, nrm, dep)
    assert out.shape == (1, 3, 21, 37)
    assert torch.allclose(out, cta, atol=1e-4)   # every level and the blending keep a constant


def test_sequence_sampler_takes_one_window_across_frames():
    scene = {k: np.arange(6 * 20 * 30 * c, dtype=np.float32).reshape(6, 20, 30, c)
             for k, c in (("cta", 3), ("albedo", 3), ("normal01", 3), ("depth01", 1),
                          ("target", 3))}
    s = SequenceSampler([scene], crop=8, frames=4, seed=1)
    b = s.batch(2)
    assert b["cta"].shape == (4, 2, 3, 8, 8)
    assert b["depth01"].shape == (4, 2, 1, 8, 8)
    # Consecutive frames differ by exactly one frame's worth of values (same window, no gain on
    # albedo).
    step = 20 * 30 * 3
    d = (b["albedo"][1] - b["albedo"][0]).abs()
    assert torch.allclose(d, torch.full_like(d, step))


def test_export_metadata(tmp_path):
    net = mrkp.MRKP(width=8)
    export(str(tmp_path / "m.afnw"), net, "mrkp")
    tensors, meta = loads((tmp_path / "m.afnw").read_bytes())
    assert meta["format"] == "mrkp" and meta["width"] == "8"
    assert set(tensors) == set(net.state_dict())


def test_costs_are_recorded():
    o = onnd.cost_per_pixel(onnd.ONND())
    m = mrkp.cost_per_pixel(mrkp.MRKP())
    assert o["parameters"] * 4 < 1_000_000 and m["parameters"] * 4 < 1_000_000  # < 1 MB weights
    assert 20_000 < o["flop_per_pixel"] < 200_000
    assert 20_000 < m["flop_per_pixel"] < 200_000
