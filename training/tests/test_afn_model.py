# SPDX-License-Identifier: Apache-2.0
"""AFN model: shapes, kernel normalisation, Eq. 3 on a hand case, ablation switches, cost, SMAPE."""

import os
import sys

import pytest
import torch

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from afn.color import tonemap  # noqa: E402
from afn.loss import smape  # noqa: E402
from afn.model import (AFN, AFNConfig, apply_kernels, cost_per_pixel, fuse,  # noqa: E402
                       pad_to_multiple)
from afn_inputs import random_inputs  # noqa: E402


@pytest.mark.parametrize("h,w", [(16, 16), (21, 37), (1, 1), (9, 8)])
def test_shapes_and_normalisation(h, w):
    net = AFN(AFNConfig(enc=(4, 4, 4), dec=(4, 4), refine=4))
    out = net(*random_inputs(h, w))
    assert out["o"].shape == (2, 3, h, w)
    hp, wp = -(-h // 8) * 8, -(-w // 8) * 8
    assert out["k_ta"].shape == (2, 49, hp, wp)
    assert out["k_1spp"].shape == (2, 49, hp // 2, wp // 2)
    assert torch.allclose(out["k_ta"].sum(1), torch.ones(1), atol=1e-5)
    assert torch.allclose(out["k_1spp"].sum(1), torch.ones(1), atol=1e-5)
    assert float(out["alpha"].min()) >= 0 and float(out["alpha"].max()) <= 1


def test_softmax_is_safe_for_huge_logits():
    net = AFN(AFNConfig(variant="fusion", enc=(4, 4, 4), dec=(4, 4)))
    with torch.no_grad():
        net.headTA.bias.fill_(1e4)
        net.head1.bias[0] = 1e4
    out = net(*random_inputs(8, 8, 1))
    assert torch.isfinite(out["o"]).all()


def test_apply_kernels_identity_and_shift():
    img = torch.arange(2 * 5 * 6, dtype=torch.float32).reshape(1, 2, 5, 6)
    k = torch.zeros(1, 49, 5, 6)
    k[:, 24] = 1.0                       # centre tap: identity
    assert torch.equal(apply_kernels(img, k), img)
    k = torch.zeros(1, 49, 5, 6)
    k[:, 3 * 7 + 4] = 1.0                # dy = 0, dx = +1: reads the right neighbour, 0 outside
    expect = torch.zeros_like(img)
    expect[..., :, :-1] = img[..., :, 1:]
    assert torch.equal(apply_kernels(img, k), expect)


def test_apply_kernels_matches_unfold():
    g = torch.Generator().manual_seed(3)
    img = torch.rand(1, 3, 9, 11, generator=g)
    k = torch.softmax(torch.randn(1, 49, 9, 11, generator=g), 1)
    unf = torch.nn.functional.unfold(img, 7, padding=3).view(1, 3, 49, 9, 11)
    ref = (unf * k[:, None]).sum(2)
    assert torch.allclose(apply_kernels(img, k), ref, atol=1e-6)


def test_fusion_eq3_hand_case():
    # One 2x2 block: d_TA = [[1, 2], [3, 6]] (mean 3), d_1spp = 5, alpha = 0.5 everywhere:
    # i = d_TA - 0.5 * 3 + 0.5 * 5 = d_TA + 1.
    d_ta = torch.tensor([[1.0, 2.0], [3.0, 6.0]]).view(1, 1, 2, 2)
    d1 = torch.tensor([[5.0]]).view(1, 1, 1, 1)
    alpha = torch.full((1, 1, 2, 2), 0.5)
    assert torch.equal(fuse(d_ta, d1, alpha), d_ta + 1)
    # alpha = 1 replaces the low frequencies of d_TA by d_1spp; alpha = 0 keeps d_TA.
    assert torch.equal(fuse(d_ta, d1, torch.zeros(1, 1, 2, 2)), d_ta)
    assert torch.equal(fuse(d_ta, d1, torch.ones(1, 1, 2, 2)), d_ta - 3 + 5)


def test_ablation_switches():
    c1, cta, alb, nrm, dep = random_inputs(16, 16, 1)
    small = dict(enc=(4, 4, 4), dec=(4, 4), refine=4)
    nets = {}
    for v in ("full", "fusion", "1spp", "ta"):
        torch.manual_seed(0)
        nets[v] = AFN(AFNConfig(variant=v, **small))
    assert hasattr(nets["full"], "ref1") and not hasattr(nets["fusion"], "ref1")
    # 1spp: the TA input is ignored; ta: the 1-spp input is ignored.
    a = nets["1spp"](c1, cta, alb, nrm, dep)["o"]
    b = nets["1spp"](c1, cta * 7 + 1, alb, nrm, dep)["o"]
    assert torch.equal(a, b)
    a = nets["ta"](c1, cta, alb, nrm, dep)["o"]
    b = nets["ta"](c1 * 3 + 2, cta, alb, nrm, dep)["o"]
    assert torch.equal(a, b)
    # fusion = full without refinement (same seed => same kernel-prediction weights)
    full = nets["full"](c1, cta, alb, nrm, dep)
    fus = nets["fusion"](c1, cta, alb, nrm, dep)
    assert torch.equal(full["i"], fus["i"])
    assert not torch.equal(full["o"], fus["o"])
    with pytest.raises(ValueError, match="unknown AFN variant"):
        AFN(AFNConfig(variant="nope"))


def test_pad_replicates_edges():
    x = torch.arange(3.0).view(1, 1, 1, 3)
    p = pad_to_multiple(x)
    assert p.shape == (1, 1, 8, 8)
    assert float(p[0, 0, 7, 7]) == 2.0 and float(p[0, 0, 5, 0]) == 0.0


def test_cost_matches_docstring():
    c = cost_per_pixel()
    # kernel prediction by hand: 2*9*(13*16/4 + 16*32/16 + 32*64/64 + 96*32/16 + 48*24/4)
    #                            + 2*(24*49/4 + 37*50)
    kp = 2 * 9 * (13 * 16 / 4 + 16 * 32 / 16 + 32 * 64 / 64 + 96 * 32 / 16 + 48 * 24 / 4) \
        + 2 * (24 * 49 / 4 + 37 * 50)
    assert c["kernel_prediction"] == kp == 15016
    assert c["refinement"] == 2 * 9 * (10 * 16 + 16 * 16 + 16 * 3) == 8352
    assert c["parameters"] == 70432


def test_gradients_flow():
    net = AFN(AFNConfig(enc=(4, 4, 4), dec=(4, 4), refine=4))
    c1, cta, alb, nrm, dep = random_inputs(8, 8, 1)
    smape(net(c1, cta, alb, nrm, dep)["o"] * alb, cta * alb).backward()
    assert all(p.grad is not None and torch.isfinite(p.grad).all() for p in net.parameters())


def test_smape_and_tonemap_hand_values():
    o = torch.tensor([1.0, 0.0, 2.0])
    t = torch.tensor([3.0, 0.0, 2.0])
    # |1-3|/(1+3+1e-3) = 2/4.001; 0/(1e-3) = 0; 0
    assert abs(float(smape(o, t)) - (2 / 4.001) / 3) < 1e-7
    x = torch.tensor([-1.0, 0.0, 2.0 ** -2.2, 4.0])
    assert torch.allclose(tonemap(x), torch.tensor([0.0, 0.0, 0.5, 1.0]))


def test_tonemap_gradient_is_finite_and_bounded():
    import torch
    from afn import color
    x = torch.tensor([-1.0, 0.0, 1e-30, 1e-6, 0.5, 1.0, 3.0], requires_grad=True)
    y = color.tonemap(x)
    assert torch.equal(y.detach(), torch.clamp(torch.clamp(x.detach(), min=0) ** (1 / 2.2), 0, 1))
    y.sum().backward()
    g = x.grad
    assert torch.isfinite(g).all() and g.max() < 100
    assert g[0] == 0 and g[1] == 0 and g[5] == 0 and g[6] == 0       # outside (0, 1): flat
    assert torch.isclose(g[4], torch.tensor(0.5 ** (1 / 2.2 - 1) / 2.2))  # exact inside
