# SPDX-License-Identifier: Apache-2.0
"""afn.widen: a wider AFN computes what the narrow one did, and its added units can learn."""

import os
import sys

import pytest
import torch

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from afn import widen  # noqa: E402
from afn.model import AFN, AFNConfig  # noqa: E402
from afn.weights import load_model, save_model  # noqa: E402
from afn_inputs import random_inputs  # noqa: E402


@pytest.mark.parametrize("variant", ["full", "fusion"])
def test_widened_model_computes_the_same(variant):
    torch.manual_seed(0)
    narrow = AFN(AFNConfig(variant=variant, enc=(4, 6, 8), dec=(6, 5), refine=4, spp=16))
    for p in narrow.parameters():          # not the default init: every weight matters
        p.data.normal_(0, 0.3)
    wide = widen.widen(narrow, enc=(7, 9, 12), dec=(8, 6), refine=6)
    assert wide.cfg.enc == (7, 9, 12) and wide.cfg.dec == (8, 6) and wide.cfg.refine == 6
    assert wide.cfg.spp == 16 and wide.cfg.variant == variant
    x = random_inputs(24, 40, seed=1)
    with torch.no_grad():
        a, b = narrow(*x), wide(*x)
    for k in ("o", "alpha", "k_ta", "k_1spp"):
        assert torch.allclose(a[k], b[k], atol=1e-5, rtol=1e-5), k
    # The added units compute something (not dead), and one training step moves the output.
    assert wide.enc1.weight[4:].abs().sum() > 0 and wide.enc1.bias[4:].abs().sum() > 0
    opt = torch.optim.Adam(wide.parameters(), lr=1e-2)
    loss = wide(*x)["o"].mean()
    loss.backward()
    assert wide.enc3.weight[:, 6:].abs().sum() == 0              # zero before the step,
    assert wide.enc3.weight.grad[:8, 6:].abs().sum() > 0         # but with a gradient
    opt.step()
    assert wide.enc3.weight[:8, 6:].abs().sum() > 0              # weights from added units moved


def test_narrowing_is_refused_and_cli_round_trip(tmp_path):
    narrow = AFN(AFNConfig(enc=(4, 6, 8), dec=(6, 5), refine=4))
    with pytest.raises(ValueError, match="narrower"):
        widen.widen(narrow, enc=(4, 5, 8))
    src, dst = str(tmp_path / "n.afnw"), str(tmp_path / "w.afnw")
    save_model(src, narrow)
    widen.main([src, "--enc", "8,8,8", "-o", dst])
    wide = load_model(dst)
    assert wide.cfg.enc == (8, 8, 8) and wide.cfg.dec == (6, 5)
    x = random_inputs(16, 16, seed=1)
    with torch.no_grad():
        assert torch.allclose(narrow(*x)["o"], wide(*x)["o"], atol=1e-5)
    with pytest.raises(SystemExit, match="narrower"):
        widen.main([src, "--dec", "2,2", "-o", dst])


def _grow_random_model(tmp_path, flag):
    """A small random model and what ``afn.widen`` FLAG makes of it, read back from its archive."""
    torch.manual_seed(0)
    old = AFN(AFNConfig(enc=(4, 6, 8), dec=(6, 5), refine=4))
    for p in old.parameters():
        p.data.normal_(0, 0.3)
    src, dst = str(tmp_path / "old.afnw"), str(tmp_path / "grown.afnw")
    save_model(src, old)
    widen.main([src, flag, "-o", dst])
    return old, load_model(dst)


def test_growing_the_history_input_keeps_the_output_and_the_input_then_matters(tmp_path):
    """widen --history: the 14th input's weights are zero, so any history01 gives the old output;
    the grown model is saved and read back with the flag, and after a training step the input
    changes the output."""
    old, grown = _grow_random_model(tmp_path, "--history")
    assert grown.cfg.history and grown.enc1.weight.shape[1] == 14
    assert grown.headTA.weight.shape[1] == 5 + 14
    x = random_inputs(24, 40, seed=1)
    h_a = torch.rand(x[0].shape[0], 1, 24, 40)
    with torch.no_grad():
        ref = old(*x)["o"]
        assert torch.allclose(grown(*x, h_a)["o"], ref, atol=1e-5)
        assert torch.allclose(grown(*x, torch.ones_like(h_a))["o"], ref, atol=1e-5)
    with pytest.raises(ValueError, match="history01"):
        grown(*x)
    with pytest.raises(ValueError, match="only growth"):
        widen.widen(grown, history=False)
    opt = torch.optim.Adam(grown.parameters(), lr=1e-2)
    (grown(*x, h_a)["o"] * torch.randn_like(ref)).mean().backward()
    opt.step()
    with torch.no_grad():
        assert not torch.allclose(grown(*x, h_a)["o"], grown(*x, torch.ones_like(h_a))["o"])


def test_growing_the_albedo_trust_starts_near_the_old_output_and_the_head_then_matters(tmp_path):
    """widen --albedo-trust: headG starts at t = sigmoid(-6), so a' = a + 0.0025 (1 - a) and,
    for albedos of 0.2 and more, the output moves by about a percent; the flag survives the
    archive, and a training step moves the head off its constant."""
    old, grown = _grow_random_model(tmp_path, "--albedo-trust")
    assert grown.cfg.albedo_trust and tuple(grown.headG.weight.shape) == (1, 4, 3, 3)
    x = list(random_inputs(24, 40, seed=1))
    x[2] = 0.2 + 0.8 * x[2]
    with torch.no_grad():
        ref, out = old(*x)["o"], grown(*x)
        assert torch.all(out["t"] < 0.003)
        remod = x[2].clamp(min=1.0 / 1024)
        assert ((out["o"] - ref) * remod).abs().max() < 0.02 * (ref * remod).abs().max()
    with pytest.raises(ValueError, match="only growth"):
        widen.widen(grown, albedo_trust=False)
    opt = torch.optim.Adam(grown.parameters(), lr=1e-2)
    (grown(*x)["o"] * torch.randn_like(ref)).mean().backward()
    opt.step()
    assert grown.headG.weight.abs().max() > 0


def test_albedo_trust_at_one_filters_the_colour_itself():
    """t = 1 is colour-space filtering: the remodulated output does not depend on how the colour
    was split into albedo and irradiance (a noisy albedo with the same colour gives the same
    result); t = 0 is the paper's demodulation."""
    torch.manual_seed(0)
    net = AFN(AFNConfig(enc=(4, 6, 8), dec=(6, 5), refine=4, variant="fusion",
                        albedo_trust=True)).eval()
    c1, cta, alb, nrm, dep = random_inputs(24, 40, seed=2)
    alb = alb.clamp(min=0.05)
    colour1, colourta = c1 * alb, cta * alb
    noisy = (alb * (0.5 + torch.rand_like(alb))).clamp(0.05, 1.0)
    with torch.no_grad():
        net.headG.bias.fill_(60.0)          # t = 1 everywhere
        a = net(colour1 / alb, colourta / alb, alb, nrm, dep)
        b = net(colour1 / noisy, colourta / noisy, noisy, nrm, dep)
        # the kernels see the network input (which differs), so compare with shared kernels:
        # the scale makes the filtered colour alb-independent, shown on the rescaled inputs
        assert torch.allclose(a["t"], torch.ones_like(a["t"]))
        from afn.model import albedo_trust_scale
        s_a = albedo_trust_scale(alb, a["t"])
        s_b = albedo_trust_scale(noisy, b["t"])
        assert torch.allclose(colour1 / alb * s_a, colour1, rtol=1e-5)
        assert torch.allclose(colour1 / noisy * s_b, colour1, rtol=1e-5)
        net.headG.bias.fill_(-60.0)         # t = 0: the paper's demodulation
        c = net(colour1 / alb, colourta / alb, alb, nrm, dep)
        assert torch.allclose(albedo_trust_scale(alb, c["t"]), torch.ones_like(alb))
