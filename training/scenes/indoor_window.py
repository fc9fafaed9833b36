# SPDX-License-Identifier: Apache-2.0
"""Scene: room lit by the sun through a window only (mostly indirect light), slow camera dolly."""

import bpy

import _common as c

DESCRIPTION = "closed room lit through one window by sun and sky; mostly indirect light"
COVERS = ["indoor", "indirect", "hard_shadows", "soft_shadows", "slow_camera", "glossy"]
DEFAULTS = {
    "sun_power": 25.0,  # sun irradiance, W/m^2
    "dolly_speed": 0.04,  # metres per frame
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.sky(scene, 1.0, sun_elevation=30.0, sun_rotation=180.0)
    wall = c.principled("wall", (0.8, 0.78, 0.72), roughness=0.95)
    floor = c.textured("parquet", 12.0, (0.45, 0.3, 0.18), (0.35, 0.22, 0.12), roughness=0.3,
                       kind="brick")
    c.room((7.0, 7.0), 3.0, wall, floor, window=(rng.uniform(-1.5, 1.5), 1.6, 1.6, 1.4))
    c.light("SUN", (0.0, 10.0, 8.0), p["sun_power"], rotation=(-0.75, rng.uniform(-0.3, 0.3), 0.0))
    sofa = c.add(bpy.ops.mesh.primitive_cube_add, c.principled("sofa", (0.2, 0.3, 0.6), 0.8),
                 size=1.0, location=(-1.8, 0.5, 0.4))
    sofa.scale = (1.0, 2.2, 0.8)
    c.add(bpy.ops.mesh.primitive_cylinder_add, c.principled("table", (0.6, 0.6, 0.6), 0.15, 1.0),
          radius=0.6, depth=0.7, location=(0.5, 0.5, 0.35))
    c.add(bpy.ops.mesh.primitive_uv_sphere_add, c.principled("vase", (0.9, 0.4, 0.2), 0.05),
          smooth=True, radius=0.2, location=(0.5, 0.5, 0.9))
    cam, _ = c.camera(scene, (2.6, -3.0, 1.6), (-0.5, 1.0, 0.8), lens=22.0)
    d = p["dolly_speed"] * (last - first)
    c.move(cam, first, last, (2.6, -3.0, 1.6), (2.6 - d, -3.0 + d, 1.6))
    return p
