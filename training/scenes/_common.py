# SPDX-License-Identifier: Apache-2.0
"""Building blocks shared by the procedural training scenes (run inside Blender 3.4).

Every helper works in metres, radians and Blender's world axes (+Z up). Animation helpers key at
integer frames; interpolation is linear unless stated (constant for switches), so motion between
keys has constant velocity and the Vector pass matches it.
"""

import math

import bpy


def clear():
    """Start from an empty factory scene and return it."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return bpy.context.scene


def principled(name, color, roughness=0.5, metallic=0.0, transmission=0.0, ior=1.45,
               emission=None, strength=0.0):
    """Principled BSDF material; ``color`` linear RGB 0..1, ``strength`` emission multiplier."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return mat


def emission(name, color, strength):
    """Pure emission material (no BSDF); ``strength`` radiance multiplier."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    em = nodes.new("ShaderNodeEmission")
    em.inputs["Color"].default_value = (*color, 1.0)
    em.inputs["Strength"].default_value = strength
    links.new(em.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    return mat


def textured(name, scale, color1, color2, roughness=0.7, kind="checker"):
    """Diffuse-ish material with a procedural ``checker``, ``brick`` or ``noise`` base colour."""
    mat = principled(name, color1, roughness=roughness)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    if kind == "brick":
        tex = nodes.new("ShaderNodeTexBrick")
        tex.inputs["Color1"].default_value = (*color1, 1.0)
        tex.inputs["Color2"].default_value = (*color2, 1.0)
        tex.inputs["Mortar"].default_value = (0.05, 0.05, 0.05, 1.0)
    elif kind == "noise":
        tex = nodes.new("ShaderNodeTexNoise")
        tex.inputs["Detail"].default_value = 8.0
    else:
        tex = nodes.new("ShaderNodeTexChecker")
        tex.inputs["Color1"].default_value = (*color1, 1.0)
        tex.inputs["Color2"].default_value = (*color2, 1.0)
    tex.inputs["Scale"].default_value = scale
    links.new(tex.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def add(op, material=None, name=None, smooth=False, **kwargs):
    """Run a primitive-add operator, assign ``material``; return the new object."""
    op(**kwargs)
    obj = bpy.context.active_object
    if material is not None:
        obj.data.materials.append(material)
    if smooth:
        bpy.ops.object.shade_smooth()
    if name:
        obj.name = name
    return obj


def sky(scene, strength, sun_elevation=35.0, sun_rotation=0.0, sun_disc=False):
    """Nishita physical sky as world light; angles in degrees; ``sun_disc`` adds a hard sun."""
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    tex = world.node_tree.nodes.new("ShaderNodeTexSky")
    tex.sky_type = "NISHITA"
    tex.sun_disc = sun_disc
    tex.sun_size = math.radians(1.5)
    tex.sun_elevation = math.radians(sun_elevation)
    tex.sun_rotation = math.radians(sun_rotation)
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Strength"].default_value = strength
    world.node_tree.links.new(tex.outputs["Color"], bg.inputs["Color"])
    return world


def flat_world(scene, color, strength):
    """Uniform world colour (dim ambient for indoor scenes)."""
    world = bpy.data.worlds.new("flat")
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*color, 1.0)
    bg.inputs["Strength"].default_value = strength
    return world


def light(kind, location, power, size=0.0, color=(1.0, 1.0, 1.0), rotation=(0.0, 0.0, 0.0)):
    """Add a light; ``power`` watts (sun: W/m^2), ``size`` metres (area) or radius (point/spot)."""
    bpy.ops.object.light_add(type=kind, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.data.energy = power
    obj.data.color = color
    if kind == "AREA":
        obj.data.size = size
    elif kind in ("POINT", "SPOT"):
        obj.data.shadow_soft_size = size
    return obj


def camera(scene, location, target, lens=35.0):
    """Add a camera at ``location`` tracking an empty at ``target``; return (camera, target)."""
    bpy.ops.object.empty_add(location=target)
    aim = bpy.context.active_object
    bpy.ops.object.camera_add(location=location)
    cam = bpy.context.active_object
    cam.data.lens = lens
    track = cam.constraints.new("TRACK_TO")
    track.target = aim
    track.track_axis = "TRACK_NEGATIVE_Z"
    track.up_axis = "UP_Y"
    scene.camera = cam
    return cam, aim


def key(target, frame, constant=False, **values):
    """Key ``values`` (attribute name -> value) on ``target`` at ``frame``.

    ``constant`` makes the new keys step (abrupt switch) instead of linear.
    """
    for name, value in values.items():
        setattr(target, name, value)
        target.keyframe_insert(data_path=name, frame=frame)
    interp = "CONSTANT" if constant else "LINEAR"
    owner = target.id_data
    ad = owner.animation_data
    if ad is None or ad.action is None:
        return
    for fc in ad.action.fcurves:
        for kp in fc.keyframe_points:
            if kp.co[0] == frame:
                kp.interpolation = interp
        if not constant:
            fc.extrapolation = "LINEAR"


def move(obj, first, last, start, end, **extra):
    """Move ``obj`` linearly from ``start`` (at ``first``) to ``end`` (at ``last``).

    ``extra`` maps an attribute to a (value_at_first, value_at_last) pair.
    """
    key(obj, first, location=start, **{k: v[0] for k, v in extra.items()})
    key(obj, last, location=end, **{k: v[1] for k, v in extra.items()})


def room(size, height, wall_mat, floor_mat, window=None):
    """Closed box room centred at the origin (floor z=0). ``window``: (x, z, w, h) hole in +Y wall."""
    sx, sy = size
    parts = [
        ("floor", (0, 0, 0), (sx, sy, 0.02), floor_mat),
        ("ceiling", (0, 0, height), (sx, sy, 0.02), wall_mat),
        ("wall_w", (-sx / 2, 0, height / 2), (0.02, sy, height), wall_mat),
        ("wall_e", (sx / 2, 0, height / 2), (0.02, sy, height), wall_mat),
        ("wall_s", (0, -sy / 2, height / 2), (sx, 0.02, height), wall_mat),
    ]
    if window is None:
        parts.append(("wall_n", (0, sy / 2, height / 2), (sx, 0.02, height), wall_mat))
    else:
        wx, wz, ww, wh = window
        left, right = wx - ww / 2 + sx / 2, sx / 2 - (wx + ww / 2)
        parts += [
            ("wall_n_l", (-sx / 2 + left / 2, sy / 2, height / 2), (left, 0.02, height), wall_mat),
            ("wall_n_r", (sx / 2 - right / 2, sy / 2, height / 2), (right, 0.02, height), wall_mat),
            ("wall_n_b", (wx, sy / 2, (wz - wh / 2) / 2), (ww, 0.02, wz - wh / 2), wall_mat),
            ("wall_n_t", (wx, sy / 2, (wz + wh / 2 + height) / 2), (ww, 0.02, height - wz - wh / 2),
             wall_mat),
        ]
    for name, loc, dims, mat in parts:
        obj = add(bpy.ops.mesh.primitive_cube_add, mat, name=name, size=1.0, location=loc)
        obj.scale = dims
