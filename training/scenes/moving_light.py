# SPDX-License-Identifier: Apache-2.0
"""Scene: static camera, an area light sweeping over objects (moving soft shadows)."""

import bpy

import _common as c

DESCRIPTION = "static camera; a large area light sweeps across, soft shadows move"
COVERS = ["moving_light_static_camera", "soft_shadows", "glossy"]
DEFAULTS = {
    "light_speed": 0.3,  # metres per frame
    "light_size": 2.0,  # area light edge, metres (soft shadows)
    "light_power": 250.0,  # watts
    "objects": 6,
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.flat_world(scene, (0.6, 0.7, 0.9), 0.05)
    c.add(bpy.ops.mesh.primitive_plane_add,
          c.textured("floor", 6.0, (0.6, 0.55, 0.5), (0.3, 0.28, 0.25), kind="noise"), size=20.0)
    ops = [bpy.ops.mesh.primitive_cube_add, bpy.ops.mesh.primitive_uv_sphere_add,
           bpy.ops.mesh.primitive_cone_add, bpy.ops.mesh.primitive_cylinder_add]
    for i in range(int(p["objects"])):
        col = (rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9))
        mat = c.principled("obj%d" % i, col, roughness=rng.choice([0.15, 0.4, 0.8]))
        op = ops[i % len(ops)]
        c.add(op, mat, location=(rng.uniform(-3, 3), rng.uniform(-1.5, 2), 0.5))
    lamp = c.light("AREA", (-4.0, -1.0, 4.0), p["light_power"], size=p["light_size"])
    travel = p["light_speed"] * (last - first)
    c.key(lamp, first, location=(-travel / 2, -1.0, 4.0))
    c.key(lamp, last, location=(travel / 2, -1.0, 4.0))
    c.camera(scene, (0.5, -9.0, 4.0), (0.0, 0.5, 0.3), lens=40.0)
    return p
