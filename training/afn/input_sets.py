# SPDX-License-Identifier: Apache-2.0
"""Input sets of the AFN models (lib/core/methods/afn/input_set.h is the C++ side).

A model is trained for one input set: the colour plus a subset of albedo, normal, depth and a
temporal history (motion vectors, or world positions with a camera). Its weights archive names
the set in the metadata key ``inputs`` ("color" or e.g. "albedo,normal"); an archive without the
key is the full set.

Training data for a smaller set: the full-set features (dataset.load_scene) with the parts outside
the set replaced by :func:`mask`, the rule the C++ filter applies (lib/core/methods/afn/network_inputs.cpp,
NetworkInputs) when a model uses fewer inputs than the frame has: absent roles at their neutral
values (albedo 1 with the colour itself as c1, normal01 0.5, depth01 0) and, without the temporal
history, the current frame as the TA input. A file that lacks those roles gives the same inputs
except that its aux prefilter (noisy 1-spp albedo/normal) ran without the missing guides;
``afntool --aov ROLE=none`` prepares such a file's inputs exactly (:func:`aov_overrides`).
"""

import numpy as np

ALBEDO_EPSILON = 2.0 ** -10      # lib/core/stages/demodulate.h kAlbedoEpsilon
MAX_IRRADIANCE = 1e15            # kMaxIrradiance

PARTS = ("albedo", "normal", "depth", "temporal")
FULL = ",".join(PARTS)
# Input-set part -> the afntool roles unbound when the part is absent.
ROLES = {"albedo": ("albedo",), "normal": ("normal",), "depth": ("depth",),
         "temporal": ("motion", "position")}


def parse(text):
    """Canonical key of an input set ("color" or parts in PARTS order); ValueError if unknown.

    Example:
        >>> parse("normal+albedo")
        'albedo,normal'
    """
    words = {w.strip() for w in text.replace("+", ",").split(",") if w.strip()}
    unknown = words - set(PARTS) - {"color"}
    if unknown:
        raise ValueError(f"unknown input-set part(s) {', '.join(sorted(unknown))} "
                         f"(known: color, {', '.join(PARTS)})")
    parts = [p for p in PARTS if p in words]
    return ",".join(parts) if parts else "color"


def aov_overrides(key):
    """afntool ``--aov`` values (``ROLE=none``) that prepare the inputs of input set ``key``."""
    present = set(parse(key).split(","))
    return [f"{role}=none" for p in PARTS if p not in present for role in ROLES[p]]


def mask(scene, key):
    """The inputs of a model for input set ``key`` from full-set features (NetworkInputs rule).

    Args:
        scene: dict of (F, H, W, C) float32 arrays with keys c1, cta, albedo, normal01, depth01
            (dataset.KEYS); not modified.
        key: an input set (:func:`parse` spelling).

    Returns:
        a new dict with the same keys and shapes.
    """
    present = set(parse(key).split(","))
    out = dict(scene)
    if "albedo" not in present:
        factor = np.maximum(scene["albedo"], ALBEDO_EPSILON)
        out["c1"] = np.minimum(scene["c1"] * factor, MAX_IRRADIANCE).astype(np.float32)
        out["cta"] = np.minimum(scene["cta"] * factor, MAX_IRRADIANCE).astype(np.float32)
        out["albedo"] = np.ones_like(scene["albedo"])
    if "normal" not in present:
        out["normal01"] = np.full_like(scene["normal01"], 0.5)
    if "depth" not in present:
        out["depth01"] = np.zeros_like(scene["depth01"])
    if "temporal" not in present:
        out["cta"] = out["c1"]
    return out
