# SPDX-License-Identifier: Apache-2.0
"""Scene: dark street lit mostly by emissive neon tubes; a glossy car-like box drives by."""

import bpy

import _common as c

DESCRIPTION = "night scene lit by emissive tubes and panels; glossy box moves through"
COVERS = ["emissive", "glossy", "moving_objects", "soft_shadows"]
DEFAULTS = {
    "tubes": 6,
    "emission_strength": 12.0,
    "drive_speed": 0.3,  # metres per frame
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.flat_world(scene, (0.02, 0.03, 0.08), 1.0)
    c.add(bpy.ops.mesh.primitive_plane_add,
          c.principled("asphalt", (0.05, 0.05, 0.05), roughness=0.35), size=30.0)
    back = c.add(bpy.ops.mesh.primitive_cube_add,
                 c.textured("facade", 10.0, (0.3, 0.3, 0.35), (0.2, 0.2, 0.22), kind="brick"),
                 size=1.0, location=(0.0, 3.0, 2.0))
    back.scale = (14.0, 0.4, 4.0)
    for i in range(int(p["tubes"])):
        col = [(1.0, 0.1, 0.6), (0.1, 0.8, 1.0), (1.0, 0.6, 0.1), (0.5, 1.0, 0.2)][rng.randrange(4)]
        x = -5.0 + 10.0 * i / max(1, int(p["tubes"]) - 1)
        c.add(bpy.ops.mesh.primitive_cylinder_add, c.emission("neon%d" % i, col,
              p["emission_strength"]), radius=0.05, depth=rng.uniform(0.8, 2.0),
              location=(x, 2.75, rng.uniform(1.0, 3.0)), rotation=(0.0, rng.choice([0, 1.5708]), 0.0))
    c.add(bpy.ops.mesh.primitive_plane_add, c.emission("sign", (1.0, 1.0, 0.9), 4.0), size=1.0,
          location=(rng.uniform(-3, 3), 2.7, 3.2), rotation=(1.5708, 0.0, 0.0))
    car = c.add(bpy.ops.mesh.primitive_cube_add,
                c.principled("car", (0.7, 0.05, 0.05), roughness=0.1, metallic=0.6),
                size=1.0, location=(-6.0, 0.3, 0.5))
    car.scale = (2.0, 1.0, 0.8)
    d = p["drive_speed"] * (last - first)
    c.move(car, first, last, (-1.0 - d / 2, 0.3, 0.5), (-1.0 + d / 2, 0.3, 0.5))
    c.camera(scene, (1.0, -6.0, 1.6), (0.0, 1.5, 1.2), lens=30.0)
    return p
