# SPDX-License-Identifier: Apache-2.0
"""Build Blender objects for the generator's shapes (``families/props.py`` lists them).

Runs inside Blender 3.4. Every object is created at the origin with its bounding box equal to the
description's ``dims`` and its scale applied (so Object texture coordinates are in metres and
modifiers see real sizes); ``blender_build.py`` then places, rotates and animates it.
"""

import math

import bpy

from . import blender_materials as bm


def _active():
    return bpy.context.active_object


def _fit(obj, dims):
    """Scale ``obj`` so its bounding box is ``dims`` (zero entries keep that axis), apply scale."""
    current = obj.dimensions
    obj.scale = tuple(d / c if d > 0 and c > 1e-9 else 1.0 for d, c in zip(dims, current))
    bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)


def _primitive(shape):
    ops = bpy.ops.mesh
    if shape == "cube":
        ops.primitive_cube_add(size=1.0)
    elif shape == "uv_sphere":
        ops.primitive_uv_sphere_add(radius=0.5, segments=32, ring_count=16)
    elif shape == "ico_sphere":
        ops.primitive_ico_sphere_add(radius=0.5, subdivisions=2)
    elif shape == "cylinder":
        ops.primitive_cylinder_add(radius=0.5, depth=1.0, vertices=32)
    elif shape == "tube":
        ops.primitive_cylinder_add(radius=0.5, depth=1.0, vertices=32, end_fill_type="NOTHING")
    elif shape == "cone":
        ops.primitive_cone_add(radius1=0.5, depth=1.0, vertices=32)
    elif shape == "torus":
        ops.primitive_torus_add(major_radius=0.35, minor_radius=0.15, major_segments=48,
                                minor_segments=16)
    elif shape == "monkey":
        ops.primitive_monkey_add(size=1.0)
        _active().modifiers.new("smooth", "SUBSURF").levels = 1
    elif shape == "plane":
        ops.primitive_plane_add(size=1.0)
    else:
        raise ValueError(shape)
    return _active()


def _rod(params, dims):
    bpy.ops.mesh.primitive_cylinder_add(radius=params["radius"], depth=dims[2], vertices=12)
    return _active()


def _wire_grid(params, dims):
    cuts = int(params["cuts"])
    ycuts = max(2, int(round(cuts * dims[1] / max(dims[0], 1e-6))))
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=cuts, y_subdivisions=ycuts, size=1.0)
    obj = _active()
    _fit(obj, (dims[0], dims[1], 0.0))
    wire = obj.modifiers.new("wire", "WIREFRAME")
    wire.thickness = params["thickness"]
    wire.use_even_offset = False
    return obj


def _helix(params, dims):
    curve = bpy.data.curves.new("helix", "CURVE")
    curve.dimensions = "3D"
    curve.bevel_depth = params["wire"]
    curve.bevel_resolution = 2
    spline = curve.splines.new("POLY")
    n = int(params["turns"] * 24)
    spline.points.add(n)
    r, h = dims[0] / 2.0 - params["wire"], dims[2]
    for i in range(n + 1):
        t = i / float(n)
        a = 2.0 * math.pi * params["turns"] * t
        spline.points[i].co = (r * math.cos(a), r * math.sin(a), h * (t - 0.5), 1.0)
    obj = bpy.data.objects.new("helix", curve)
    bpy.context.collection.objects.link(obj)
    return obj


def _text(params, dims):
    bpy.ops.object.text_add()
    obj = _active()
    obj.data.body = params["body"]
    obj.data.extrude = 0.05
    obj.data.align_x, obj.data.align_y = "CENTER", "CENTER"
    bpy.context.view_layer.update()
    k = dims[0] / max(obj.dimensions[0], 1e-6)
    obj.scale = (k, k, k)  # font objects cannot have their scale applied
    return obj


def _rock(params, dims):
    bpy.ops.mesh.primitive_ico_sphere_add(radius=0.5, subdivisions=3)
    obj = _active()
    tex = bpy.data.textures.new("rock", "CLOUDS")
    tex.noise_scale = params["noise_scale"] * 0.3
    disp = obj.modifiers.new("displace", "DISPLACE")
    disp.texture = tex
    disp.strength = 0.25
    disp.texture_coords = "GLOBAL"
    obj.location = (params["seed"] % 97, params["seed"] // 97 % 89, 0.0)  # picks the noise region
    bpy.context.view_layer.update()
    bpy.ops.object.modifier_apply(modifier="displace")
    obj.location = (0.0, 0.0, 0.0)
    _fit(obj, dims)
    return obj


def _hair(obj, params):
    """Add particle hair (``count`` strands of ``length`` m) with the hair material."""
    obj.data.materials.append(bm.material(params["hair_material"], "hair"))
    mod = obj.modifiers.new("hair", "PARTICLE_SYSTEM")
    psys = mod.particle_system
    psys.seed = int(params["seed"])
    part = psys.settings
    part.type = "HAIR"
    part.count = int(params["count"])
    part.hair_length = params["length"]
    # Random velocity is absolute (not relative to hair_length): keep it a share of the length.
    part.factor_random = 0.3 * part.normal_factor
    part.material = 2
    part.root_radius = 1.0
    part.tip_radius = 0.2
    part.radius_scale = params["radius_mm"] * 0.001
    part.use_emit_random = True
    part.display_step = 3
    part.render_step = 3


def build(desc):
    """Create the object for one description (``families/props.py``); return it."""
    shape, dims, params = desc["shape"], desc["dims"], desc["params"]
    if shape == "rod":
        obj = _rod(params, dims)
    elif shape == "wire_grid":
        obj = _wire_grid(params, dims)
    elif shape == "helix":
        obj = _helix(params, dims)
    elif shape == "text":
        obj = _text(params, dims)
    elif shape == "rock":
        obj = _rock(params, dims)
    else:
        obj = _primitive({"hair_ball": "uv_sphere", "grass": "plane"}.get(shape, shape))
        flat = shape in ("plane", "grass")
        _fit(obj, (dims[0], dims[1], 0.0) if flat else dims)
    obj.data.materials.append(bm.material(desc["material"]))
    if shape in ("hair_ball", "grass"):
        _hair(obj, params)
    if desc["smooth"] and obj.type == "MESH":
        for poly in obj.data.polygons:
            poly.use_smooth = True
    return obj
