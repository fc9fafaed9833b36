# SPDX-License-Identifier: Apache-2.0
"""Weights archive round trip, corruption checks, and the committed parity vectors."""

import os
import struct
import sys

import numpy as np
import pytest
import torch

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, TRAINING)
from afn import make_parity_vectors as mpv  # noqa: E402
from afn.model import AFN, AFNConfig  # noqa: E402
from afn.weights import WeightsFormatError, dumps, load_model, loads, save_model  # noqa: E402

PARITY = os.path.join(TRAINING, "..", "tests", "data", "afn_parity")


def test_round_trip(tmp_path):
    torch.manual_seed(0)
    net = AFN(AFNConfig(variant="fusion", enc=(4, 6, 8), dec=(6, 4)))
    path = tmp_path / "m.afnw"
    save_model(path, net)
    back = load_model(path)
    assert back.cfg.variant == "fusion" and back.cfg.enc == (4, 6, 8)
    for k, v in net.state_dict().items():
        assert torch.equal(v, back.state_dict()[k]), k
    data = path.read_bytes()
    assert data[:4] == b"AFNW" and struct.unpack_from("<I", data, 4)[0] == 1


def test_sample_count_is_stored_only_where_it_is_not_one(tmp_path):
    """The `spp` key the C++ core chooses models by (model_set.h); 1-spp archives stay as before."""
    torch.manual_seed(0)
    cfg = AFNConfig(enc=(4, 4, 4), dec=(4, 4), refine=4)
    save_model(tmp_path / "low.afnw", AFN(cfg))
    assert "spp" not in loads((tmp_path / "low.afnw").read_bytes())[1]
    assert load_model(tmp_path / "low.afnw").cfg.spp == 1
    cfg.spp = 16
    save_model(tmp_path / "high.afnw", AFN(cfg))
    assert loads((tmp_path / "high.afnw").read_bytes())[1]["spp"] == "16"
    assert load_model(tmp_path / "high.afnw").cfg.spp == 16


def test_training_declares_the_lowest_sample_count_it_trained_on():
    from afn import train
    base = ["--data", "d", "--out", "o"]
    assert train.model_config(train.parse_args(base)).spp == 1
    assert train.model_config(train.parse_args(base + ["--spp", "16"])).spp == 16
    assert train.model_config(train.parse_args(base + ["--spp", "64,16"])).spp == 16


def test_layout_by_hand():
    data = dumps({"a": np.array([1.5, -2.0], np.float32)}, {"k": "v"})
    # header 16 + meta "k=v\n" 4 + entry (2 + 1 + 1 + 1 + 4 + 16 = 25) = 45 -> data at 48
    assert struct.unpack_from("<4sIII", data, 0) == (b"AFNW", 1, 1, 4)
    assert data[16:20] == b"k=v\n"
    assert struct.unpack_from("<H1sBBIQQ", data, 20) == (1, b"a", 1, 1, 2, 48, 8)
    assert struct.unpack_from("<2f", data, 48) == (1.5, -2.0)
    assert len(data) == 56


@pytest.mark.parametrize("cut", [3, 15, 30, 50])
def test_truncated_is_rejected(cut):
    data = dumps({"a": np.ones((2, 3), np.float32)})
    with pytest.raises(WeightsFormatError):
        loads(data[:cut])


def test_bad_magic_version_and_size():
    data = bytearray(dumps({"a": np.ones(4, np.float32)}))
    with pytest.raises(WeightsFormatError, match="magic"):
        loads(b"XXXX" + bytes(data[4:]))
    bad = bytearray(data)
    struct.pack_into("<I", bad, 4, 2)
    with pytest.raises(WeightsFormatError, match="version"):
        loads(bytes(bad))
    bad = bytearray(data)
    struct.pack_into("<Q", bad, 16 + 2 + 1 + 2 + 4 + 8, 12)   # data size 12 != 16
    with pytest.raises(WeightsFormatError, match="corrupted"):
        loads(bytes(bad))


@pytest.mark.parametrize("variant", ["full", "fusion", "large", "quarter", "history", "trust"])
def test_committed_parity_vectors_match_this_model(variant):
    """The committed PyTorch outputs still equal this code's forward pass (regenerate with
    `python3 -m afn.make_parity_vectors` when the model changes on purpose)."""
    with open(os.path.join(PARITY, f"case_{variant}.afnw"), "rb") as f:
        case, meta = loads(f.read())
    model = load_model(os.path.join(PARITY, f"weights_{variant}.afnw"))
    out = mpv.run(model, case)
    for k in ("o", "i", "alpha1" if variant == "large" else "alpha"):
        np.testing.assert_allclose(out[k], case[k], rtol=1e-5, atol=1e-6, err_msg=k)
    # the inputs are reproducible too (history01 is in the cases of models that read it)
    for k, v in mpv.make_inputs().items():
        if k in case or k != "history01":
            np.testing.assert_array_equal(v, case[k])
    assert ("history01" in case) == (variant in ("history", "trust"))
    if variant == "trust":
        np.testing.assert_allclose(out["t"], case["t"], rtol=1e-5, atol=1e-6, err_msg="t")
