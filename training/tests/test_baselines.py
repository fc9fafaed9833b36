# SPDX-License-Identifier: Apache-2.0
"""The learned baselines (afn.baselines): WSKPN's folding and filter, NBGD's bilateral grid,
archives, the documented costs, and the committed parity vectors."""

import os
import sys

import numpy as np
import pytest
import torch

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TRAINING)
from afn.baselines import archive, nbgd, wskpn  # noqa: E402
from afn.baselines import make_parity_vectors as mpv  # noqa: E402
from afn.weights import WeightsFormatError, loads  # noqa: E402

PARITY = os.path.join(TRAINING, "..", "tests", "data", "baselines_parity")


def inputs(h=19, w=27, seed=0):
    g = torch.Generator().manual_seed(seed)
    return [torch.rand(1, 3, h, w, generator=g) * 3, torch.rand(1, 3, h, w, generator=g),
            torch.rand(1, 3, h, w, generator=g), torch.rand(1, 1, h, w, generator=g)]


def test_wskpn_folding_is_exact():
    torch.manual_seed(1)
    model = wskpn.WSKPN().eval()
    folded = wskpn.FoldedWSKPN(model.folded_state()).eval()
    x = inputs()
    with torch.no_grad():
        a, b = model(*x), folded(*x)
    assert torch.allclose(a["head"], b["head"], atol=1e-5)
    assert torch.allclose(a["o"], b["o"], atol=1e-5)
    # A folding that forgot the identity would not match.
    state = model.folded_state()
    state["conv2.weight"][:, :, 2, 2] -= torch.eye(wskpn.WIDTH)
    with torch.no_grad():
        bad = wskpn.FoldedWSKPN(state)(*x)
    assert (bad["head"] - a["head"]).abs().max() > 1e-2


def test_wskpn_equal_weights_give_box_mean():
    color = torch.rand(1, 3, 9, 11)
    head = torch.zeros(1, wskpn.HEAD_CHANNELS, 9, 11)
    head[:, len(wskpn.WINDOWS)] = 30.0          # fusion on the 3x3 window
    out = wskpn.filter_and_fuse(color, head)
    ones = torch.ones(1, 1, 9, 11)
    mean = wskpn.box_sum(color, 3) / wskpn.box_sum(ones, 3)
    assert torch.allclose(out, mean, atol=1e-5)


def test_nbgd_grid_keeps_constants_and_guide_edges():
    color = torch.full((1, 3, 24, 40), 0.25)
    color[..., 20:] = 2.0
    guide = torch.full((1, 1, 24, 40), 20.0)
    guide[..., 20:] = 200.0
    for ss, sr in nbgd.GRIDS:
        out = nbgd.bilateral_filter(color, guide, ss, sr)
        assert torch.allclose(out, color, atol=1e-5), (ss, sr)
    blurred = nbgd.bilateral_filter(color, torch.full_like(guide, 100.0), 8, 8)
    assert blurred[0, 0, 12, 19] > 0.3 and blurred[0, 0, 12, 20] < 1.9


def test_nbgd_guides_get_gradients():
    model = nbgd.NBGD()
    x = inputs()
    model(*x)["o"].sum().backward()
    assert model.guide1.weight.grad.abs().sum() > 0


def test_grid_shape_has_the_upper_neighbour():
    assert nbgd.grid_shape(144, 256, 4, 4) == (37, 65, 65)
    assert nbgd.grid_shape(21, 37, 16, 16) == (3, 4, 17)


@pytest.mark.parametrize("method", archive.METHODS)
def test_archive_round_trip(tmp_path, method):
    torch.manual_seed(2)
    model = archive.make_model(method).eval()
    path = str(tmp_path / "m.afnw")
    archive.save_model(path, method, model)
    back_method, back = archive.load_model(path)
    assert back_method == method
    x = inputs()
    with torch.no_grad():
        assert torch.allclose(model(*x)["o"], back(*x)["o"], atol=1e-5)


def test_archive_rejects_other_formats(tmp_path):
    from afn.weights import dumps
    path = tmp_path / "x.afnw"
    path.write_bytes(dumps({"a": np.zeros(2, np.float32)}, {"format": "afn"}))
    with pytest.raises(WeightsFormatError):
        archive.load_model(str(path))


def test_documented_costs():
    c = wskpn.cost_per_pixel()
    assert c["network"] == 54600 and c["parameters"] == 27382
    assert c["training_parameters"] == 38466
    n = nbgd.cost_per_pixel()
    assert n["network"] == 15000 and n["parameters"] == 7525


def test_committed_parity_vectors_are_current():
    """The committed vectors equal what make_parity_vectors writes now (same torch rounding)."""
    full = mpv.make_inputs()
    ins = {k: full[k] for k in mpv.KEYS}
    for method, (weights, outputs) in mpv.cases(ins).items():
        with open(os.path.join(PARITY, f"{method}_case.afnw"), "rb") as f:
            committed, _ = loads(f.read())
        for k, v in outputs.items():
            np.testing.assert_allclose(committed[k], v, atol=1e-5, err_msg=f"{method} {k}")
        with open(os.path.join(PARITY, f"{method}_weights.afnw"), "rb") as f:
            tensors, meta = loads(f.read())
        assert meta["format"] == method
        want, _ = loads(weights)
        for k in want:
            np.testing.assert_array_equal(tensors[k], want[k])
