# SPDX-License-Identifier: Apache-2.0
"""Object descriptions shared by the scene families (no ``bpy``).

An object is a dict: ``shape`` (one of :data:`SHAPES`), ``location`` (centre of its bounding box at
frame 0, metres), ``rotation`` (XYZ Euler, radians), ``dims`` (bounding-box size in metres before
rotation), ``material`` (see ``materials.py``), ``smooth`` (smooth shading), ``velocity`` (metres
per frame) and ``spin`` (radians per frame, per Euler axis), and ``params`` for the shapes that need
them (hair counts and lengths, wire thickness, text). ``blender_meshes.py`` builds every shape.
"""

import math

from .. import materials as mats
from .. import sampling as s

# Shapes and what they add: primitives (``tube``: a cylinder open at both ends, e.g. a lamp
# shade), thin geometry (rod, wire_grid, helix), hair-like detail (hair_ball, grass), fine
# geometry (text), irregular solids (rock).
SHAPES = ("cube", "uv_sphere", "ico_sphere", "cylinder", "tube", "cone", "torus", "monkey",
          "plane", "rod", "wire_grid", "helix", "hair_ball", "grass", "text", "rock")

PROP_SHAPES = {"cube": 1.5, "uv_sphere": 1.5, "ico_sphere": 0.7, "cylinder": 1.0, "cone": 0.6,
               "torus": 1.0, "monkey": 1.0, "rod": 0.8, "wire_grid": 0.5, "helix": 0.6,
               "hair_ball": 0.6, "text": 0.4, "rock": 0.8}

WORDS = ("afn", "noise", "render", "filter", "pixel", "light", "glass", "metal", "path", "frame")


def obj(shape, location, dims, material, rotation=(0.0, 0.0, 0.0), smooth=True, params=None):
    """A static object description."""
    if shape not in SHAPES:
        raise ValueError("unknown shape %r" % shape)
    return {"shape": shape, "location": s.vec(*location), "dims": s.vec(*dims),
            "rotation": s.vec(*rotation), "material": material, "smooth": bool(smooth),
            "velocity": [0.0, 0.0, 0.0], "spin": [0.0, 0.0, 0.0], "params": params or {}}


def box(location, dims, material, yaw=0.0):
    """Axis-aligned (up to ``yaw``) box: walls, tables, buildings."""
    return obj("cube", location, dims, material, (0.0, 0.0, yaw), smooth=False)


def shape_params(rng, shape, size):
    """Shape-specific parameters for an object about ``size`` metres across."""
    if shape == "rod":
        return {"radius": round(s.log_uniform(rng, 0.0015, 0.012), 5)}
    if shape == "wire_grid":
        return {"cuts": rng.randint(6, 30), "thickness": round(s.log_uniform(rng, 0.001, 0.006), 5)}
    if shape == "helix":
        return {"turns": round(rng.uniform(3.0, 12.0), 3),
                "wire": round(s.log_uniform(rng, 0.002, 0.01), 5)}
    if shape in ("hair_ball", "grass"):
        return {"count": rng.randint(400, 2500) if shape == "hair_ball" else rng.randint(1500, 5000),
                "length": round(size * rng.uniform(0.15, 0.5), 4),
                "radius_mm": round(rng.uniform(0.3, 1.5), 3), "seed": rng.randrange(1 << 16),
                "hair_material": mats.material(rng, rng.choice(["diffuse", "plastic", "textured"]))}
    if shape == "text":
        return {"body": rng.choice(WORDS)}
    if shape == "rock":
        return {"noise_scale": round(rng.uniform(0.5, 2.0), 3), "seed": rng.randrange(1 << 16)}
    return {}


def dims_for(rng, shape, size):
    """Bounding box (metres) of a ``shape`` about ``size`` across."""
    if shape == "rod":
        return (0.0, 0.0, size)  # radius comes from params; length is ``size``
    if shape == "wire_grid":
        return (size, size * rng.uniform(0.5, 1.0), 0.0)
    if shape in ("cylinder", "cone"):
        d = size * rng.uniform(0.4, 1.0)
        return (d, d, size)
    if shape == "torus":
        return (size, size, size * 0.3)
    if shape == "text":
        return (size, size * 0.35, size * 0.1)
    if shape == "helix":
        return (size * 0.4, size * 0.4, size)
    return tuple(size * rng.uniform(0.7, 1.3) for _ in range(3)) if shape in ("cube", "rock") \
        else (size, size, size)


def prop(rng, base, size, shape=None, material=None, weights=None, material_weights=None):
    """A random object about ``size`` m across standing on the point ``base`` (x, y, floor z)."""
    shape = shape or s.pick(rng, weights or PROP_SHAPES)
    dims = dims_for(rng, shape, size)
    params = shape_params(rng, shape, size)
    yaw = rng.uniform(0.0, 2.0 * math.pi)
    rot = (0.0, 0.0, yaw)
    if shape == "rod" and s.chance(rng, 0.5):
        rot = (math.pi / 2, 0.0, yaw)  # lying on the floor
        z = base[2] + params["radius"]
    elif shape in ("wire_grid", "text"):
        rot = (math.pi / 2, 0.0, yaw)  # standing like a fence, a screen or a sign
        z = base[2] + dims[1] / 2
    else:
        z = base[2] + (dims[2] / 2 if dims[2] > 0 else size / 2)
    mat = material or mats.material(rng, weights=material_weights)
    return obj(shape, (base[0], base[1], z), dims, mat, rot,
               smooth=shape not in ("cube", "rock", "wire_grid"), params=params)


def inside(point, o, margin=0.05):
    """True when ``point`` lies inside (or within ``margin`` of) object ``o``'s volume.

    Upright objects (no X/Y rotation) use their yawed bounding box; others a bounding sphere.
    Flat shapes (planes, grass) have no inside.
    """
    if o["shape"] in ("plane", "grass") or o["dims"][2] <= 0 and o["shape"] != "rod":
        return False
    d = [point[i] - o["location"][i] for i in range(3)]
    rx, ry, yaw = o["rotation"]
    if abs(rx) > 1e-6 or abs(ry) > 1e-6:
        return math.sqrt(sum(x * x for x in d)) < max(o["dims"]) / 2 + margin
    c, s_ = math.cos(-yaw), math.sin(-yaw)
    local = (c * d[0] - s_ * d[1], s_ * d[0] + c * d[1], d[2])
    return all(abs(local[i]) <= o["dims"][i] / 2 + margin for i in range(3))


def make_moving(rng, o, speed, spin=0.0, vertical=0.0):
    """Give ``o`` a constant velocity of ``speed`` m/frame and a spin up to ``spin`` rad/frame."""
    o["velocity"] = s.linear_motion(rng, speed, vertical)
    o["spin"] = s.vec(*(rng.uniform(-spin, spin) for _ in range(3)))
    return o


def scatter(rng, count, half_extent, min_gap=0.0, avoid=None):
    """``count`` random (x, y) points in a square of ``half_extent``, at least ``min_gap`` apart.

    ``avoid`` is an (x, y, radius) disc kept free (e.g. where the camera looks from).
    """
    points = []
    for _ in range(count * 20):
        if len(points) == count:
            break
        p = (rng.uniform(-half_extent, half_extent), rng.uniform(-half_extent, half_extent))
        if avoid and math.hypot(p[0] - avoid[0], p[1] - avoid[1]) < avoid[2]:
            continue
        if all(math.hypot(p[0] - q[0], p[1] - q[1]) >= min_gap for q in points):
            points.append(p)
    return points
