# SPDX-License-Identifier: Apache-2.0
"""Scenes of a generated dataset (``training/generate-dataset``, format ``afn-dataset-2``).

Layout (docs/dataset.md)::

    ROOT/manifest.json                       "format": "afn-dataset-2", one record per sequence
    ROOT/<split>/<family>-<seed>/spp<S>/frame.NNNN.exr       S samples per pixel
    ROOT/<split>/<family>-<seed>/spp<S>/reference.NNNN.exr   what frame.NNNN.exr is scored against

``<split>`` is ``train`` (levels 1, 4, 16, 64; each level's reference is the leave-one-out target,
independent of that level's noise) or ``eval`` (levels 1, 16; clean references). Every level
folder is a scene in the sense of :mod:`afn.dataset`: afntool reads it as it reads any rendered
sequence. A scene is named ``<family>-<seed>/spp<S>``; only sequences the manifest records as
complete are listed, so a dataset can be read while its render goes on.
"""

import json
import os

FORMAT = "afn-dataset-2"


def manifest(root):
    """The manifest of a generated dataset at ``root``, or None for any other folder."""
    path = os.path.join(root, "manifest.json")
    if not os.path.isfile(path):
        return None
    with open(path) as f:
        m = json.load(f)
    return m if m.get("format") == FORMAT else None


def parse_levels(text):
    """Sample counts from ``"1"``, ``"16,64"`` or a list; None or empty -> None."""
    if text is None or text == "":
        return None
    if isinstance(text, int):
        return [text]
    items = text.split(",") if isinstance(text, str) else list(text)
    levels = [int(x) for x in items if str(x).strip()]
    if not levels or any(s < 1 for s in levels):
        raise ValueError(f"sample counts must be positive integers, not {text!r}")
    return levels


def scenes(root, m, spp):
    """{``<seq>/spp<S>``: folder} of complete sequences for every level S in ``spp``.

    Args:
        root: the dataset folder.
        m: its manifest (:func:`manifest`).
        spp: list of sample counts to select (each must be a level of the dataset).

    Returns:
        (scenes, evaluation scene names): the dict sorted by name, and the names from the ``eval``
        split (never trained on).
    """
    if not spp:
        raise ValueError(f"{root} is a generated dataset with levels {m.get('levels')} (training) "
                         f"and {m.get('eval_levels')} (evaluation): choose levels with --spp")
    known = {int(s) for key in ("levels", "eval_levels")
             for s in str(m.get(key, "")).split(",") if s}
    unknown = [s for s in spp if s not in known]
    if unknown:
        raise ValueError(f"{root}: no level {unknown[0]} spp (levels: "
                         f"{', '.join(str(s) for s in sorted(known))})")
    out, evals = {}, set()
    for name, rec in sorted(m.get("sequences", {}).items()):
        if not rec.get("complete"):
            continue
        for s in spp:
            if s not in rec.get("levels", []):
                continue
            key = f"{name}/spp{s}"
            out[key] = os.path.join(root, rec["dir"], f"spp{s}")
            if rec.get("split") == "eval":
                evals.add(key)
    return out, evals


def expand(names, available):
    """Scene names from user names: ``room-0000003`` stands for all its selected levels.

    Raises:
        KeyError: a name matches no scene.
    """
    out = []
    for n in names:
        hits = [s for s in available if s == n or s.startswith(n.rstrip("/") + "/")]
        if not hits:
            raise KeyError(n)
        out += [h for h in hits if h not in out]
    return out
