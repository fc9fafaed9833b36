# SPDX-License-Identifier: Apache-2.0
"""Procedural scene of the bundled example sequence, built from parameters and a seed (Blender 3.4).

Content: a diffuse floor with a high-frequency checker/noise texture, a mirror-like sphere, a glossy
(rough metal) torus, a diffuse cube that slides and spins across the floor, an emissive sphere, an
area light and a physical sky. The camera dollies slowly sideways while looking at the centre.
Frames are numbered from ``first_frame``; all motion is linear in the frame number.
"""

import math
import random

import bpy

DEFAULTS = {
    "frames": 8,  # frame count; motion is scaled so the whole move spans this many frames
    "camera_shift": 0.08,  # camera dolly per frame, metres
    "cube_speed": 0.25,  # cube slide per frame, metres
    "cube_spin": 6.0,  # cube spin per frame, degrees
    "sky_strength": 0.08,  # multiplier on the Nishita sky radiance
    "light_power": 400.0,  # area light power, watts
    "emission_strength": 8.0,  # emissive sphere radiance multiplier
}


def _clear():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return bpy.context.scene


def _material(name, color, roughness=0.5, metallic=0.0, emission=None, strength=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return mat


def _floor_material(rng):
    mat = _material("floor", (0.5, 0.5, 0.5), roughness=0.8)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    checker = nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = rng.uniform(18.0, 26.0)  # high-frequency pattern
    checker.inputs["Color1"].default_value = (0.75, 0.72, 0.65, 1.0)
    checker.inputs["Color2"].default_value = (0.12, 0.14, 0.18, 1.0)
    noise = nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 40.0
    mix = nodes.new("ShaderNodeMixRGB")
    mix.blend_type = "MULTIPLY"
    mix.inputs["Fac"].default_value = 0.35
    links.new(checker.outputs["Color"], mix.inputs["Color1"])
    links.new(noise.outputs["Color"], mix.inputs["Color2"])
    links.new(mix.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def _add(obj_op, material, **kwargs):
    obj_op(**kwargs)
    obj = bpy.context.active_object
    obj.data.materials.append(material)
    return obj


def _sky(scene, strength):
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    sky = world.node_tree.nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    sky.sun_disc = False  # the area light casts the shadows; keep the sky smooth
    sky.sun_elevation = math.radians(35.0)
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Strength"].default_value = strength
    world.node_tree.links.new(sky.outputs["Color"], bg.inputs["Color"])


def _key(obj, frame, **values):
    for name, value in values.items():
        setattr(obj, name, value)
        obj.keyframe_insert(data_path=name, frame=frame)


def build(params, seed, first_frame=0):
    """Build the scene into a fresh file; return it. ``params`` overrides DEFAULTS."""
    p = dict(DEFAULTS)
    p.update(params or {})
    rng = random.Random(seed)
    scene = _clear()
    n = int(p["frames"])
    scene.frame_start, scene.frame_end = first_frame, first_frame + n - 1

    floor = _add(bpy.ops.mesh.primitive_plane_add, _floor_material(rng), size=30.0)
    floor.name = "floor"
    mirror = _add(bpy.ops.mesh.primitive_uv_sphere_add,
                  _material("mirror", (0.9, 0.9, 0.92), roughness=0.02, metallic=1.0),
                  radius=1.0, location=(rng.uniform(-0.3, 0.3), 1.2, 1.0), segments=64, ring_count=32)
    bpy.ops.object.shade_smooth()
    mirror.name = "mirror"
    hue = rng.random()
    gold = (0.9, 0.6 + 0.2 * hue, 0.25)
    torus = _add(bpy.ops.mesh.primitive_torus_add,
                 _material("glossy", gold, roughness=0.25, metallic=1.0),
                 location=(2.4, 1.8, 0.45), major_radius=0.8, minor_radius=0.3,
                 rotation=(math.radians(20.0), 0.0, 0.0))
    bpy.ops.object.shade_smooth()
    torus.name = "glossy"
    cube_col = (0.7 * rng.random() + 0.2, 0.15, 0.6 * rng.random() + 0.1)
    cube = _add(bpy.ops.mesh.primitive_cube_add, _material("cube", cube_col, roughness=0.6),
                size=0.9, location=(-1.8, -0.4, 0.45))
    cube.name = "cube"
    lamp = _add(bpy.ops.mesh.primitive_uv_sphere_add,
                _material("emitter", (0.1, 0.1, 0.1), emission=(1.0, 0.55, 0.2),
                          strength=p["emission_strength"]),
                radius=0.35, location=(-1.7, 2.6, 0.35))
    lamp.name = "emitter"

    bpy.ops.object.light_add(type="AREA", location=(2.0, -1.5, 5.0))
    light = bpy.context.active_object
    light.data.energy = p["light_power"]
    light.data.size = 1.5
    light.rotation_euler = (math.radians(20.0), math.radians(15.0), 0.0)
    _sky(scene, p["sky_strength"])

    bpy.ops.object.empty_add(location=(0.0, 1.2, 0.4))
    target = bpy.context.active_object
    bpy.ops.object.camera_add(location=(-0.3, -7.0, 3.4))
    cam = bpy.context.active_object
    cam.data.lens = 35.0
    track = cam.constraints.new("TRACK_TO")
    track.target = target
    track.track_axis = "TRACK_NEGATIVE_Z"
    track.up_axis = "UP_Y"
    scene.camera = cam

    last = first_frame + n - 1
    cx, cy, cz = cam.location
    _key(cam, first_frame, location=(cx, cy, cz))
    _key(cam, last, location=(cx + p["camera_shift"] * (n - 1), cy, cz))
    _key(cube, first_frame, location=(-1.8, -0.4, 0.45), rotation_euler=(0.0, 0.0, 0.0))
    _key(cube, last, location=(-1.8 + p["cube_speed"] * (n - 1), -0.4, 0.45),
         rotation_euler=(0.0, 0.0, math.radians(p["cube_spin"] * (n - 1))))
    from afn_render import set_linear

    set_linear(cam)
    set_linear(cube)
    return scene, p
