# SPDX-License-Identifier: Apache-2.0
"""Scene: closed room whose lamp switches off and another changes colour abruptly."""

import bpy

import _common as c

DESCRIPTION = "indoor room; ceiling lamp switches off/on and a spot changes colour abruptly"
COVERS = ["light_switch", "indoor", "soft_shadows", "slow_camera"]
DEFAULTS = {
    "switch_period": 4,  # frames between switches
    "lamp_power": 300.0,  # watts
    "spot_power": 600.0,  # watts
}

COLOURS = [(1.0, 0.2, 0.1), (0.1, 0.4, 1.0), (0.2, 1.0, 0.3), (1.0, 0.9, 0.6)]


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.flat_world(scene, (0.0, 0.0, 0.0), 0.0)
    wall = c.principled("wall", (0.75, 0.72, 0.68), roughness=0.9)
    floor = c.textured("floor", 8.0, (0.5, 0.35, 0.2), (0.3, 0.2, 0.1), kind="brick")
    c.room((8.0, 8.0), 3.0, wall, floor)
    for i in range(4):
        col = (rng.uniform(0.2, 0.9), rng.uniform(0.2, 0.9), rng.uniform(0.2, 0.9))
        c.add(bpy.ops.mesh.primitive_cube_add, c.principled("box%d" % i, col, roughness=0.5),
              size=rng.uniform(0.5, 1.0), location=(rng.uniform(-2.5, 2.5), rng.uniform(-1, 2.5), 0.4))
    lamp = c.light("AREA", (0.0, 0.0, 2.9), p["lamp_power"], size=1.0)
    spot = c.light("SPOT", (-3.0, -3.0, 2.5), p["spot_power"], size=0.05,
                   rotation=(0.9, 0.0, -0.8))
    period = max(1, int(p["switch_period"]))
    start = rng.randrange(len(COLOURS))
    for k, f in enumerate(range(first, last + 1, period)):
        c.key(lamp.data, f, constant=True, energy=p["lamp_power"] if k % 2 == 0 else 0.0)
        c.key(spot.data, f, constant=True, color=COLOURS[(start + k) % len(COLOURS)])
    cam, _ = c.camera(scene, (2.5, -3.6, 1.8), (0.0, 1.0, 0.6), lens=24.0)
    c.key(cam, first, location=(2.5, -3.6, 1.8))
    c.key(cam, last, location=(2.5 - 0.03 * (last - first), -3.6, 1.8))
    return p
