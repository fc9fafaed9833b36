# SPDX-License-Identifier: Apache-2.0
"""Scene: thin fence posts, a wire grid and high-frequency textures under a fast camera pan."""

import bpy

import _common as c

DESCRIPTION = "thin posts and wires, fine brick/checker textures, fast lateral camera pan"
COVERS = ["fine_geometry", "high_frequency_texture", "fast_camera", "outdoor_sky", "hard_shadows"]
DEFAULTS = {
    "posts": 40,  # fence posts
    "post_radius": 0.02,  # metres (thinner than a pixel at 320x180 from afar)
    "wires": 12,
    "pan_speed": 0.35,  # camera metres per frame (fast)
    "texture_scale": 300.0,  # checker cells across the 40 m floor (13 cm cells)
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.sky(scene, 0.06, sun_elevation=25.0, sun_rotation=rng.uniform(0, 360), sun_disc=True)
    c.add(bpy.ops.mesh.primitive_plane_add,
          c.textured("floor", p["texture_scale"], (0.8, 0.8, 0.8), (0.05, 0.05, 0.05)), size=40.0)
    wall = c.add(bpy.ops.mesh.primitive_cube_add,
                 c.textured("wall", 25.0, (0.6, 0.3, 0.2), (0.5, 0.5, 0.5), kind="brick"),
                 size=1.0, location=(0.0, 3.0, 1.5))
    wall.scale = (16.0, 0.3, 3.0)
    metal = c.principled("wire", (0.6, 0.6, 0.6), roughness=0.3, metallic=1.0)
    n = int(p["posts"])
    for i in range(n):
        x = -8.0 + 16.0 * i / max(1, n - 1)
        c.add(bpy.ops.mesh.primitive_cylinder_add, metal, vertices=8, radius=p["post_radius"],
              depth=2.0, location=(x + rng.uniform(-0.05, 0.05), 0.5, 1.0))
    for j in range(int(p["wires"])):
        z = 0.2 + 1.7 * j / max(1, int(p["wires"]) - 1)
        c.add(bpy.ops.mesh.primitive_cylinder_add, metal, vertices=6, radius=0.008, depth=16.0,
              location=(0.0, 0.5, z), rotation=(0.0, 1.5708, 0.0))
    cam, aim = c.camera(scene, (0.0, -5.0, 1.4), (0.0, 1.0, 1.0), lens=35.0)
    span = p["pan_speed"] * (last - first)
    c.move(cam, first, last, (-span / 2, -5.0, 1.4), (span / 2, -5.0, 1.4))
    c.move(aim, first, last, (-span / 2, 1.0, 1.0), (span / 2, 1.0, 1.0))
    return p
