# SPDX-License-Identifier: Apache-2.0
"""AFN large (model_large.py): shapes, normalisation, constancy of filtering + fusion, the unused
TA input, the progressive fusion on a hand case, export round trip, training and export CLIs."""

import os
import sys

import pytest
import torch

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TRAINING)
from afn import export, model_large  # noqa: E402
from afn.model import AFN, AFNConfig, cost_per_pixel, make_model  # noqa: E402
from afn.weights import load_model, loads, save_model  # noqa: E402
from afn_inputs import random_inputs  # noqa: E402

SMALL = dict(variant="large", enc=(4, 6, 8), dec=(6, 5), refine=4)


def _model(seed=0, **kw):
    torch.manual_seed(seed)
    return make_model(AFNConfig(**{**SMALL, **kw})).eval()


@pytest.mark.parametrize("h,w", [(16, 16), (21, 37), (1, 1), (9, 8)])
def test_shapes_and_normalisation(h, w):
    with torch.no_grad():
        out = _model()(*random_inputs(h, w))
    hp, wp = -(-h // 8) * 8, -(-w // 8) * 8
    assert out["o"].shape == (2, 3, h, w)
    assert out["k1"].shape == (2, 25, hp, wp)
    assert out["k2"].shape == (2, 25, hp // 2, wp // 2)
    assert out["k3"].shape == (2, 25, hp // 4, wp // 4)
    for k in ("k1", "k2", "k3"):
        assert torch.allclose(out[k].sum(1), torch.ones(1), atol=1e-5), k
    for a in ("alpha1", "alpha2"):
        assert 0 <= float(out[a].min()) and float(out[a].max()) <= 1


def test_make_model_builds_the_large_graph_and_afn_refuses_it():
    assert isinstance(_model(), model_large.AFNLarge)
    with pytest.raises(ValueError, match="make_model"):
        AFN(AFNConfig(variant="large"))


def test_constant_image_stays_constant_through_filtering_and_fusion():
    """Edge-replicated 5x5 kernels and Eq. 3 per scale keep a constant exactly constant (borders
    included); only the learned refinement may move it."""
    net = _model(seed=3)
    with torch.no_grad():      # far-from-uniform kernels and fusion weights
        for name in ("head1", "head2", "head3"):
            getattr(net, name).weight.mul_(5.0)
        c = torch.full((1, 3, 21, 37), 2.5)
        out = net(c, c, *random_inputs(21, 37, 1)[2:])
    for k in ("f1", "f2", "f3", "o2", "i"):
        assert torch.allclose(out[k], torch.full_like(out[k], 2.5), rtol=1e-5), k


def test_ta_input_is_not_used():
    net = _model()
    c, cta, alb, nrm, dep = random_inputs()
    with torch.no_grad():
        a = net(c, cta, alb, nrm, dep)["o"]
        b = net(c, torch.zeros_like(cta), alb, nrm, dep)["o"]
    assert torch.equal(a, b)


def test_fusion_takes_low_frequencies_from_the_coarser_scale():
    fine = torch.arange(16, dtype=torch.float32).reshape(1, 1, 4, 4)
    coarse = torch.tensor([[[[100.0, 200.0], [300.0, 400.0]]]])
    assert torch.equal(model_large.fuse_scale(fine, coarse, torch.zeros(1, 1, 4, 4)), fine)
    full = model_large.fuse_scale(fine, coarse, torch.ones(1, 1, 4, 4))
    # alpha 1: the coarse value plus the fine pixel's deviation from its 2x2 block mean.
    assert float(full[0, 0, 0, 0]) == pytest.approx(100.0 + 0.0 - 2.5)
    assert torch.allclose(model_large.down2(full), coarse)


def test_apply_kernels5_identity_and_edge_replication():
    img = torch.arange(2 * 5 * 6, dtype=torch.float32).reshape(1, 2, 5, 6)
    k = torch.zeros(1, 25, 5, 6)
    k[:, 12] = 1.0                       # centre tap
    assert torch.equal(model_large.apply_kernels5(img, k), img)
    k = torch.zeros(1, 25, 5, 6)
    k[:, 2 * 5 + 4] = 1.0                # dy = 0, dx = +2: the right border repeats
    out = model_large.apply_kernels5(img, k)
    assert torch.equal(out[..., :-2], img[..., 2:])
    assert torch.equal(out[..., -1], img[..., -1]) and torch.equal(out[..., -2], img[..., -1])


def test_cost_and_size_of_the_default_architecture():
    cost = cost_per_pixel(AFNConfig(variant="large"))
    n = sum(p.numel() for p in make_model(AFNConfig(variant="large")).parameters())
    assert cost["parameters"] == n
    assert n * 4 < 400_000                # "a few hundred KB" in the repository
    afn = cost_per_pixel(AFNConfig())
    assert cost["refinement"] == pytest.approx(2 * afn["refinement"])


def test_export_round_trip(tmp_path):
    net = _model(spp=64)
    path = tmp_path / "large.afnw"
    save_model(path, net)
    meta = loads(path.read_bytes())[1]
    assert meta["variant"] == "large" and meta["spp"] == "64"
    back = load_model(path)
    assert isinstance(back, model_large.AFNLarge) and back.cfg.spp == 64
    x = random_inputs(13, 19, 1)
    with torch.no_grad():
        assert torch.equal(net(*x)["o"], back(*x)["o"])


def test_export_command_writes_a_large_archive(tmp_path):
    net = _model(spp=16)
    ck = tmp_path / "latest.pt"
    torch.save({"model": net.state_dict(), "config": net.cfg.to_dict(), "epoch": 3}, ck)
    out = tmp_path / "out.afnw"
    export.main([str(ck), "-o", str(out)])
    assert loads(out.read_bytes())[1]["variant"] == "large"
    assert isinstance(load_model(out), model_large.AFNLarge)


def test_train_command_trains_and_exports_the_large_variant(tmp_path):
    """`afn.train --variant large` on the committed example sequence (smoke: one tiny epoch)."""
    pytest.importorskip("OpenImageIO")
    sequence = os.path.join(TRAINING, "..", "examples", "sequence")
    if not os.path.exists(os.path.join(sequence, "frame.0000.exr")):
        pytest.skip("examples/sequence not present")
    from afn import train
    out = str(tmp_path / "run")
    train.main(["--data", sequence, "--out", out, "--variant", "large", "--steps", "1",
                "--batch", "2", "--crop", "32", "--max-frames", "2", "--enc", "4,4,4",
                "--dec", "4,4", "--refine", "4", "--device", "cpu", "--epochs", "1"])
    model = load_model(os.path.join(out, "model.afnw"))
    assert isinstance(model, model_large.AFNLarge) and model.cfg.enc == (4, 4, 4)
