# SPDX-License-Identifier: Apache-2.0
"""Random inputs of the AFN networks, shared by the model tests."""

import torch


def random_inputs(h=21, w=37, b=2, seed=0):
    """``(c1, cta, albedo, normal01, depth01)``, each (b, C, h, w), drawn in that order from one
    generator seeded with ``seed``: c1 in [0, 4), the others in [0, 1); depth01 has 1 channel."""
    g = torch.Generator().manual_seed(seed)
    c1 = torch.rand(b, 3, h, w, generator=g) * 4
    cta = torch.rand(b, 3, h, w, generator=g)
    alb = torch.rand(b, 3, h, w, generator=g)
    nrm = torch.rand(b, 3, h, w, generator=g)
    dep = torch.rand(b, 1, h, w, generator=g)
    return c1, cta, alb, nrm, dep
