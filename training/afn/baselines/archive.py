# SPDX-License-Identifier: Apache-2.0
"""Baseline models in the weights archive (.afnw, :mod:`afn.weights`) that the C++ methods embed.

Metadata ``format`` names the method. ``wskpn`` archives hold the folded inference network
(``conv1`` ... ``conv6``, 5x5; :meth:`WSKPN.folded_state`), never the training branches;
``nbgd`` archives hold the guide network (``guide1``, ``guide2``).
"""

import torch

from ..weights import WeightsFormatError, dumps, loads
from . import nbgd, wskpn

METHODS = ("wskpn", "nbgd")


def make_model(method):
    """A fresh training model of ``method``."""
    if method == "wskpn":
        return wskpn.WSKPN()
    if method == "nbgd":
        return nbgd.NBGD()
    raise ValueError(f"unknown baseline '{method}' (known: {', '.join(METHODS)})")


def archive_bytes(method, model):
    """The .afnw bytes of a training model (WSKPN folded)."""
    state = model.folded_state() if method == "wskpn" else model.state_dict()
    return dumps(state, {"format": method})


def save_model(path, method, model):
    with open(path, "wb") as f:
        f.write(archive_bytes(method, model))


def load_model(path):
    """(method, inference model in eval mode) from an archive written by :func:`save_model`."""
    with open(path, "rb") as f:
        tensors, meta = loads(f.read())
    method = meta.get("format")
    state = {k: torch.from_numpy(v) for k, v in tensors.items()}
    if method == "wskpn":
        return method, wskpn.FoldedWSKPN(state).eval()
    if method == "nbgd":
        m = nbgd.NBGD()
        m.load_state_dict(state)
        return method, m.eval()
    raise WeightsFormatError(f"{path}: not a baseline archive (format '{method}')")
