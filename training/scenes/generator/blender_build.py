# SPDX-License-Identifier: Apache-2.0
"""Build a generator scene description (``describe.py``) into the current Blender scene.

Runs inside Blender 3.4. Animation is keyed linearly (constant velocity between keys, linear
extrapolation), so the Vector pass matches the motion; light switches are constant (step) keys, fades
linear keys held after their last key.
"""

import math
import os

import bpy

from . import blender_materials as bm
from . import blender_meshes as meshes



def world_map_resolution(desc):
    """Importance-map size for a world description: full for environment maps, 256 otherwise."""
    return 1024 if desc["type"] == "hdri" else 256


def _key(target, frame, constant=False, **values):
    """Key ``values`` on ``target`` at ``frame``; linear (or constant) interpolation."""
    for name, value in values.items():
        setattr(target, name, value)
        target.keyframe_insert(data_path=name, frame=frame)
    ad = target.id_data.animation_data
    if ad is None or ad.action is None:
        return
    for fc in ad.action.fcurves:
        for kp in fc.keyframe_points:
            if kp.co[0] == frame:
                kp.interpolation = "CONSTANT" if constant else "LINEAR"
        if not constant:
            fc.extrapolation = "LINEAR"


def _animate(obj, location, rotation, velocity, spin, frames):
    """Place ``obj``; when it moves, key frame 0 and the last frame (at least frame 1)."""
    obj.location, obj.rotation_euler = location, rotation
    if not any(velocity) and not any(spin):
        return
    last = max(1, frames - 1)
    end_loc = [p + v * last for p, v in zip(location, velocity)]
    end_rot = [r + w * last for r, w in zip(rotation, spin)]
    _key(obj, 0, location=location, rotation_euler=rotation)
    _key(obj, last, location=end_loc, rotation_euler=end_rot)


def _aim(obj, point):
    """Point ``obj``'s -Z axis at a fixed world ``point`` with a Track To constraint."""
    bpy.ops.object.empty_add(location=point)
    empty = bpy.context.active_object
    track = obj.constraints.new("TRACK_TO")
    track.target = empty
    track.track_axis = "TRACK_NEGATIVE_Z"
    track.up_axis = "UP_Y"
    return empty


def world(scene, desc):
    """Sky, environment map or flat world."""
    w = bpy.data.worlds.new("world")
    scene.world = w
    w.use_nodes = True
    nodes, links = w.node_tree.nodes, w.node_tree.links
    bg = nodes["Background"]
    bg.inputs["Strength"].default_value = desc["strength"]
    # The world's importance map is rebuilt at every sync (first frame of every file series):
    # 1024x1024 costs ~3 s, 256x256 ~0.2 s. The bundled environment maps hold small bright suns
    # and lamps that a 256 map undersamples (fireflies: 15 dB between two 64-spp renders of a
    # street lit by the "city" map, 25 dB at 1024); the smooth Nishita sky does well at 256.
    w.cycles.sampling_method = "MANUAL"
    w.cycles.sample_map_resolution = world_map_resolution(desc)
    if desc["type"] == "sky":
        tex = nodes.new("ShaderNodeTexSky")
        tex.sky_type = "NISHITA"
        tex.sun_disc = desc["sun_disc"]
        tex.sun_size = math.radians(1.5)
        tex.sun_elevation = math.radians(desc["sun_elevation"])
        tex.sun_rotation = math.radians(desc["sun_rotation"])
        links.new(tex.outputs["Color"], bg.inputs["Color"])
    elif desc["type"] == "hdri":
        folder = bpy.utils.system_resource("DATAFILES", path="studiolights/world")
        tex = nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(os.path.join(folder, desc["name"] + ".exr"))
        coord, mapping = nodes.new("ShaderNodeTexCoord"), nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(desc["rotation"]))
        links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
        links.new(tex.outputs["Color"], bg.inputs["Color"])
    else:
        bg.inputs["Color"].default_value = (*desc["colour"], 1.0)
    return w


def light(desc, frames):
    """One light: type, power, colour, size, aim, motion and switches."""
    bpy.ops.object.light_add(type=desc["type"], location=desc["location"])
    obj = bpy.context.active_object
    data = obj.data
    data.energy, data.color = desc["power"], desc["colour"]
    if desc.get("portal"):
        data.cycles.is_portal = True
        data.shape = "RECTANGLE"
        data.size, data.size_y = desc["size"], desc["size_y"]
    elif desc["type"] == "AREA":
        data.size = desc["size"]
    elif desc["type"] == "SUN":
        data.angle = math.radians(desc["size"])
    else:
        data.shadow_soft_size = desc["size"]
        if desc["type"] == "SPOT":
            data.spot_size = math.radians(desc["spot_deg"])
            data.spot_blend = 0.3
    if desc["aim"] is not None:
        _aim(obj, desc["aim"])
    _animate(obj, desc["location"], (0.0, 0.0, 0.0), desc["velocity"], (0, 0, 0), frames)
    if desc["switch"]:
        _key(data, 0, constant=True, energy=desc["power"], color=desc["colour"])
        for frame, factor, colour in desc["switch"]:
            _key(data, frame, constant=True, energy=desc["power"] * factor, color=colour)
    if desc.get("fade"):
        for frame, factor in desc["fade"]:
            _key(data, frame, energy=desc["power"] * factor)
        for fc in data.animation_data.action.fcurves:
            fc.extrapolation = "CONSTANT"  # hold the end values, not the ramp
    return obj


def camera(scene, desc):
    """Camera keyed at every frame (location and look-at target), lens and depth of field."""
    bpy.ops.object.camera_add(location=desc["keys"][0]["location"])
    cam = bpy.context.active_object
    cam.data.lens = desc["lens"]
    cam.data.sensor_width = desc["sensor_width"]
    cam.data.sensor_fit = "HORIZONTAL"
    cam.data.clip_start = 0.01
    target = _aim(cam, desc["keys"][0]["target"])
    if len(desc["keys"]) > 1 and any(k != desc["keys"][0] for k in desc["keys"]):
        for f, k in enumerate(desc["keys"]):
            _key(cam, f, location=k["location"])
            _key(target, f, location=k["target"])
    if desc["dof"]:
        cam.data.dof.use_dof = True
        cam.data.dof.focus_distance = desc["dof"]["focus_distance"]
        cam.data.dof.aperture_fstop = desc["dof"]["fstop"]
    scene.camera = cam
    return cam


def render_settings(scene, desc):
    """Light-path limits of the description (shared by inputs and references)."""
    cyc = scene.cycles
    r = desc["render"]
    cyc.max_bounces = r["max_bounces"]
    cyc.diffuse_bounces = r["diffuse_bounces"]
    cyc.glossy_bounces = r["glossy_bounces"]
    cyc.transmission_bounces = r["transmission_bounces"]
    cyc.transparent_max_bounces = r["transparent_max_bounces"]


def build(desc):
    """Clear Blender and build ``desc``; return the scene (frames 0..frames-1)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bm.reset()
    scene = bpy.context.scene
    frames = desc["frames"]
    scene.frame_start, scene.frame_end = 0, frames - 1
    world(scene, desc["world"])
    for i, o in enumerate(desc["objects"]):
        obj = meshes.build(o)
        obj.name = "%s.%03d" % (o["shape"], i)
        _animate(obj, o["location"], o["rotation"], o["velocity"], o["spin"], frames)
    for lt in desc["lights"]:
        light(lt, frames)
    camera(scene, desc["camera"])
    scene.render.engine = "CYCLES"
    render_settings(scene, desc)
    return scene
