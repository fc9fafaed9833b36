# SPDX-License-Identifier: Apache-2.0
"""AFN's quarter-resolution scale (model.py ``quarter``): hand cases of its fusion, the near-neutral
start that lets a trained model grow it, the archive round trip and widening."""

import math
import os
import sys

import pytest
import torch

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from afn.model import (AFN, AFNConfig, KERNEL_TAPS, QUARTER_CENTRE_LOGIT,  # noqa: E402
                       cost_per_pixel, fuse_quarter, up4_bilinear)
from afn.weights import load_model, save_model  # noqa: E402
from afn.widen import widen  # noqa: E402
from afn_inputs import random_inputs  # noqa: E402


def _identity_kernels(b, h, w):
    k = torch.zeros(b, KERNEL_TAPS, h, w)
    k[:, KERNEL_TAPS // 2] = 1.0
    return k


def test_up4_bilinear_hand_values():
    # align_corners=False: output x samples (x + 0.5) / 4 - 0.5, clamped at the borders.
    src = torch.tensor([[0.0, 4.0]]).view(1, 1, 1, 2)
    got = up4_bilinear(src)[0, 0, 0]
    want = torch.tensor([0.0, 0.0, 0.5, 1.5, 2.5, 3.5, 4.0, 4.0])
    assert torch.allclose(got, want)


def test_identity_kernels_or_zero_beta_keep_the_image():
    i = torch.rand(1, 3, 16, 24)
    k_id = _identity_kernels(1, 4, 6)
    beta = torch.rand(1, 1, 4, 6)
    assert torch.allclose(fuse_quarter(i, k_id, beta), i)
    k_box = torch.full((1, KERNEL_TAPS, 4, 6), 1.0 / KERNEL_TAPS)
    assert torch.equal(fuse_quarter(i, k_box, torch.zeros(1, 1, 4, 6)), i)


def test_constant_low_band_is_replaced_by_the_filtered_one():
    # i constant 2 (a 16x16 frame, a 4x4 quarter image), a kernel that averages the pixel and
    # its right neighbour, beta 1: inside the quarter image the low band stays 2; in its last
    # column the neighbour is outside (reads 0), so the filtered low band there is 1 and the
    # upsampled delta -1 reaches the image's last 2 columns fully.
    i = torch.full((1, 3, 16, 16), 2.0)
    k = torch.zeros(1, KERNEL_TAPS, 4, 4)
    k[:, KERNEL_TAPS // 2] = 0.5
    k[:, KERNEL_TAPS // 2 + 1] = 0.5
    out = fuse_quarter(i, k, torch.ones(1, 1, 4, 4))
    assert torch.allclose(out[..., :8], i[..., :8])
    assert torch.allclose(out[..., -2:], torch.full_like(out[..., -2:], 1.0))


def test_grown_model_starts_almost_where_the_trained_one_was():
    torch.manual_seed(0)
    base = AFN(AFNConfig(enc=(8, 12, 16), dec=(12, 8), refine=8)).eval()
    grown = AFN(AFNConfig(enc=(8, 12, 16), dec=(12, 8), refine=8, quarter=True)).eval()
    missing = grown.load_state_dict(base.state_dict(), strict=False).missing_keys
    assert sorted(missing) == ["head4.bias", "head4.weight"]
    with torch.no_grad():
        a, b = base(*random_inputs(24, 40, b=1))["o"], grown(*random_inputs(24, 40, b=1))
    assert torch.equal(b["beta"], torch.full_like(b["beta"], 0.5))
    centre = b["k_q"][:, KERNEL_TAPS // 2]
    e = math.exp(QUARTER_CENTRE_LOGIT)      # softmax of one logit c among 48 zeros
    assert torch.allclose(centre, torch.full_like(centre, e / (e + KERNEL_TAPS - 1)), atol=1e-6)
    rel = ((a - b["o"]).abs().mean() / a.abs().mean()).item()
    assert 0 < rel < 0.02, rel


def test_variants_without_fusion_refuse_it():
    for variant in ("1spp", "ta"):
        with pytest.raises(ValueError, match="quarter"):
            AFN(AFNConfig(variant=variant, quarter=True))


def test_round_trip_and_widening_keep_it(tmp_path):
    torch.manual_seed(1)
    net = AFN(AFNConfig(enc=(4, 6, 8), dec=(6, 4), refine=4, quarter=True)).eval()
    with torch.no_grad():
        net.head4.bias.zero_()              # a scale that matters
    path = str(tmp_path / "q.afnw")
    save_model(path, net)
    back = load_model(path).eval()
    assert back.cfg.quarter
    wide = widen(back, enc=(8, 8, 8), dec=(8, 8)).eval()
    assert wide.cfg.quarter
    with torch.no_grad():
        a, b, c = net(*random_inputs(24, 40, b=1))["o"], back(*random_inputs(24, 40, b=1))["o"], wide(*random_inputs(24, 40, b=1))["o"]
    assert torch.equal(a, b)
    assert torch.allclose(a, c, atol=1e-5)
    plain = AFNConfig(enc=(4, 6, 8), dec=(6, 4), refine=4)
    assert (cost_per_pixel(net.cfg)["parameters"] - cost_per_pixel(plain)["parameters"]
            == 6 * (KERNEL_TAPS + 1) + KERNEL_TAPS + 1)


def test_train_only_freezes_everything_else():
    from afn.train import trainable_parameters
    torch.manual_seed(2)
    net = AFN(AFNConfig(enc=(4, 6, 8), dec=(6, 4), refine=4, quarter=True))
    before = {k: v.clone() for k, v in net.state_dict().items()}
    params = trainable_parameters(net, "head4")
    assert [id(p) for p in params] == [id(net.head4.weight), id(net.head4.bias)]
    opt = torch.optim.Adam(params, lr=1e-2)
    out = net(*random_inputs(24, 40, b=1))["o"]
    out.mean().backward()
    opt.step()
    after = net.state_dict()
    changed = sorted(k for k in after if not torch.equal(after[k], before[k]))
    assert changed == ["head4.bias", "head4.weight"]
    assert len(trainable_parameters(AFN(AFNConfig()), "")) == len(list(AFN(AFNConfig()).parameters()))
    with pytest.raises(SystemExit, match="no parameter"):
        trainable_parameters(AFN(AFNConfig()), "head9")
