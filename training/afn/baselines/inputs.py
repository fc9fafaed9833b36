# SPDX-License-Identifier: Apache-2.0
"""The network input shared by the baselines (the papers' 10 channels).

Chosen here (the papers feed "temporally accumulated demodulated colour, albedo, normals mapped to
[0, 1], normalised depth"; they do not say whether the colour is tone-mapped for the network): the
colour enters the convolutions tone-mapped, T(cta) = clip(max(x, 0)^(1/2.2), 0, 1), as afn's input
does, while the filters (WSKPN's boxes, NBGD's grids) run on the linear HDR colour.
"""

import torch

from ..color import tonemap

INPUT_CHANNELS = 10   # T(cta) 3, albedo 3, normal01 3, depth01 1


def network_input(cta, albedo, normal01, depth01):
    """(B, 10, H, W) = [T(cta), albedo, normal01, depth01]; every argument (B, C, H, W)."""
    return torch.cat([tonemap(cta), albedo, normal01, depth01], 1)
