# SPDX-License-Identifier: Apache-2.0
"""Scene: mirror and glossy spheres on a checker floor under a sunny sky, slow camera orbit."""

import math

import bpy

import _common as c

DESCRIPTION = "mirror and glossy spheres (roughness ladder) under sky + sun disc, slow orbit"
COVERS = ["glossy", "mirror", "hard_shadows", "outdoor_sky", "slow_camera"]
DEFAULTS = {
    "spheres": 5,  # sphere count
    "orbit_deg_per_frame": 0.6,  # camera orbit speed, degrees per frame
    "sun_elevation": 40.0,  # degrees
    "sky_strength": 0.05,  # sky (with sun disc) radiance multiplier
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used (with random draws)."""
    scene = c.clear()
    p = dict(p)
    p["sun_rotation"] = round(rng.uniform(0.0, 360.0), 1)
    c.sky(scene, p["sky_strength"], p["sun_elevation"], p["sun_rotation"], sun_disc=True)
    c.add(bpy.ops.mesh.primitive_plane_add,
          c.textured("floor", rng.uniform(10, 30), (0.7, 0.7, 0.7), (0.15, 0.15, 0.15)), size=40.0)
    n = int(p["spheres"])
    for i in range(n):
        rough = 0.02 + 0.5 * i / max(1, n - 1)
        tint = (rng.uniform(0.5, 1.0), rng.uniform(0.5, 1.0), rng.uniform(0.5, 1.0))
        x = (i - (n - 1) / 2) * 1.4
        c.add(bpy.ops.mesh.primitive_uv_sphere_add,
              c.principled("metal%d" % i, tint, roughness=rough, metallic=1.0),
              smooth=True, radius=0.6, location=(x, rng.uniform(-0.5, 0.5), 0.6),
              segments=48, ring_count=24)
    cam, _ = c.camera(scene, (0.0, -8.0, 2.5), (0.0, 0.0, 0.5))
    radius, height = 8.0, 2.5
    a0 = math.radians(rng.uniform(-20, 20))
    for f in (first, last):
        a = a0 + math.radians(p["orbit_deg_per_frame"]) * (f - first)
        c.key(cam, f, location=(radius * math.sin(a), -radius * math.cos(a), height))
    return p
