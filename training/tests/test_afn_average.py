# SPDX-License-Identifier: Apache-2.0
"""afn.average: checkpoint averaging of .afnw models."""

import os
import sys

import pytest
import torch

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from afn import average  # noqa: E402
from afn.model import AFNConfig, make_model  # noqa: E402
from afn.weights import load_model, save_model  # noqa: E402


def tiny(path, seed, **kw):
    torch.manual_seed(seed)
    m = make_model(AFNConfig(enc=(4, 4, 4), dec=(4, 4), refine=4, **kw))
    save_model(str(path), m)
    return m.state_dict()


def test_mean_of_every_tensor_and_metadata_kept(tmp_path):
    a = tiny(tmp_path / "a.afnw", 1, spp=16)
    b = tiny(tmp_path / "b.afnw", 2, spp=16)
    c = tiny(tmp_path / "c.afnw", 3, spp=16)
    out = tmp_path / "mean.afnw"
    average.main([str(tmp_path / f"{n}.afnw") for n in "abc"] + ["-o", str(out)])
    m = load_model(str(out))
    assert m.cfg.spp == 16 and m.cfg.enc == (4, 4, 4)
    for k, v in m.state_dict().items():
        assert torch.allclose(v, (a[k] + b[k] + c[k]) / 3, rtol=0, atol=1e-7), k
    assert any(not torch.equal(a[k], b[k]) for k in a)     # the inputs did differ


def test_other_architecture_or_sample_count_is_refused(tmp_path):
    tiny(tmp_path / "a.afnw", 1)
    tiny(tmp_path / "b.afnw", 2, spp=16)
    with pytest.raises(SystemExit, match="another architecture"):
        average.main([str(tmp_path / "a.afnw"), str(tmp_path / "b.afnw"), "-o",
                      str(tmp_path / "x.afnw")])
    assert not os.path.exists(tmp_path / "x.afnw")
    with pytest.raises(SystemExit):
        average.main([str(tmp_path / "missing.afnw"), "-o", str(tmp_path / "x.afnw")])
