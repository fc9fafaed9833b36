# SPDX-License-Identifier: Apache-2.0
"""Scene families of the generator: name -> ``layout(rng, frames)`` (see ``interiors.py``)."""

from .exteriors import atrium, kinetic, night, outdoor
from .interiors import clutter, room, showroom, tabletop

FAMILIES = {
    "tabletop": tabletop,
    "room": room,
    "showroom": showroom,
    "clutter": clutter,
    "outdoor": outdoor,
    "night": night,
    "kinetic": kinetic,
    "atrium": atrium,
}
