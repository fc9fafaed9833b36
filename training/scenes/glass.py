# SPDX-License-Identifier: Apache-2.0
"""Scene: refractive glass objects, one rolling across a textured floor, sky light."""

import bpy

import _common as c

DESCRIPTION = "glass sphere, cube and monkey over a textured floor; one glass ball rolls"
COVERS = ["refraction", "transparent", "moving_objects", "outdoor_sky", "slow_camera"]
DEFAULTS = {
    "ior": 1.45,
    "roll_speed": 0.2,  # metres per frame
    "sky_strength": 0.12,
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.sky(scene, p["sky_strength"], sun_elevation=50.0, sun_rotation=rng.uniform(0, 360))
    c.add(bpy.ops.mesh.primitive_plane_add,
          c.textured("floor", 14.0, (0.9, 0.85, 0.2), (0.1, 0.2, 0.6)), size=30.0)
    tint = (rng.uniform(0.8, 1.0), rng.uniform(0.8, 1.0), rng.uniform(0.8, 1.0))
    glass = c.principled("glass", tint, roughness=0.0, transmission=1.0, ior=p["ior"])
    frosted = c.principled("frosted", (0.9, 0.95, 1.0), roughness=0.25, transmission=1.0,
                           ior=p["ior"])
    c.add(bpy.ops.mesh.primitive_cube_add, frosted, size=1.0, location=(1.5, 1.0, 0.5),
          rotation=(0.0, 0.0, rng.uniform(0, 1.5)))
    c.add(bpy.ops.mesh.primitive_monkey_add, glass, smooth=True, size=1.2,
          location=(-1.5, 1.2, 0.7), rotation=(0.3, 0.0, 0.3))
    ball = c.add(bpy.ops.mesh.primitive_uv_sphere_add, glass, smooth=True, radius=0.5,
                 location=(-2.0, -1.0, 0.5), segments=48, ring_count=24)
    d = p["roll_speed"] * (last - first)
    c.move(ball, first, last, (-2.0, -1.0, 0.5), (-2.0 + d, -1.0, 0.5),
           rotation_euler=((0.0, 0.0, 0.0), (0.0, d / 0.5, 0.0)))
    c.light("AREA", (3.0, -2.0, 5.0), 300.0, size=1.0, rotation=(0.4, 0.4, 0.0))
    cam, _ = c.camera(scene, (0.0, -6.5, 2.6), (0.0, 0.5, 0.5), lens=35.0)
    c.move(cam, first, last, (0.0, -6.5, 2.6), (0.03 * (last - first), -6.5 - 0.02 * (last - first), 2.6))
    return p
