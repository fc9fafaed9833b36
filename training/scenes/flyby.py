# SPDX-License-Identifier: Apache-2.0
"""Scene: outdoor field of objects, several flying/tumbling, camera flies fast past them."""

import bpy

import _common as c

DESCRIPTION = "outdoor sky, many tumbling moving objects, fast forward camera flight"
COVERS = ["outdoor_sky", "fast_camera", "moving_objects", "hard_shadows", "glossy"]
DEFAULTS = {
    "objects": 14,
    "flight_speed": 0.5,  # camera metres per frame
    "object_speed": 0.25,  # metres per frame
}


def build(p, rng, first, last):
    """Build the scene; return the parameters actually used."""
    scene = c.clear()
    c.sky(scene, 0.03, sun_elevation=rng.uniform(15, 60), sun_rotation=rng.uniform(0, 360),
          sun_disc=True)
    c.add(bpy.ops.mesh.primitive_plane_add,
          c.textured("grass", 3.0, (0.2, 0.4, 0.1), (0.1, 0.2, 0.05), kind="noise"), size=80.0)
    ops = [bpy.ops.mesh.primitive_cube_add, bpy.ops.mesh.primitive_ico_sphere_add,
           bpy.ops.mesh.primitive_torus_add, bpy.ops.mesh.primitive_cone_add]
    n = last - first
    for i in range(int(p["objects"])):
        col = (rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0))
        mat = c.principled("o%d" % i, col, roughness=rng.choice([0.05, 0.3, 0.7]),
                           metallic=rng.choice([0.0, 1.0]))
        start = (rng.uniform(-6, 6), rng.uniform(0, 20), rng.uniform(0.5, 3.0))
        obj = c.add(ops[i % len(ops)], mat, location=start)
        if i % 2 == 0:
            v = p["object_speed"] * n
            end = (start[0] + rng.uniform(-v, v), start[1] + rng.uniform(-v, v), start[2])
            c.move(obj, first, last, start, end,
                   rotation_euler=((0.0, 0.0, 0.0), (0.1 * n, 0.07 * n, 0.0)))
    cam, aim = c.camera(scene, (0.0, -8.0, 1.8), (0.0, 5.0, 1.0), lens=28.0)
    d = p["flight_speed"] * n
    c.move(cam, first, last, (0.0, -8.0, 1.8), (0.5, -8.0 + d, 1.8))
    c.move(aim, first, last, (0.0, 5.0, 1.0), (0.5, 5.0 + d, 1.0))
    return p
