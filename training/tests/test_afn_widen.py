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


def test_growing_the_history_input_keeps_the_output_and_the_input_then_matters(tmp_path):
    """widen --history: the 14th input's weights are zero, so any history01 gives the old output;
    the grown model is saved and read back with the flag, and after a training step the input
    changes the output."""
    torch.manual_seed(0)
    old = AFN(AFNConfig(enc=(4, 6, 8), dec=(6, 5), refine=4))
    for p in old.parameters():
        p.data.normal_(0, 0.3)
    src, dst = str(tmp_path / "old.afnw"), str(tmp_path / "grown.afnw")
    save_model(src, old)
    widen.main([src, "--history", "-o", dst])
    grown = load_model(dst)
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
