# SPDX-License-Identifier: Apache-2.0
"""Indoor and close-up scene families: ``tabletop``, ``room``, ``showroom`` and ``clutter``.

Each ``layout(rng, frames)`` returns ``objects``, ``lights``, ``world``, the camera ``rig`` (see
``camera.py``) and ``effects`` (chances of depth of field, motion blur, moving and switching
lights); ``describe.py`` adds the camera path and the effects.
"""

import math

from .. import lighting as L
from .. import materials as mats
from .. import sampling as s
from . import props as P


def tabletop(rng, frames):
    """A handful of props of mixed scale on a table, studio or environment lighting, close camera."""
    objects = [P.box((0, 0, -0.025), (rng.uniform(2.0, 4.0), rng.uniform(1.5, 3.0), 0.05),
                     mats.ground(rng, fine=s.chance(rng, 0.5)))]
    if s.chance(rng, 0.6):  # backdrop wall
        objects.append(P.box((0, rng.uniform(0.8, 1.4), 1.0), (4.0, 0.05, 2.0),
                             mats.material(rng, weights={"diffuse": 3, "textured": 2})))
    for x, y in P.scatter(rng, rng.randint(4, 9), 0.6, min_gap=0.18):
        o = P.prop(rng, (x, y, 0.0), s.log_uniform(rng, 0.04, 0.35))
        if s.chance(rng, 0.25):
            P.make_moving(rng, o, s.log_uniform(rng, 0.003, 0.04), spin=0.08)
        objects.append(o)
    lights = []
    for _ in range(rng.randint(1, 3)):
        pos = s.on_circle((0, 0, 0), rng.uniform(1.0, 2.5), rng.uniform(0, 2 * math.pi),
                          rng.uniform(0.8, 2.5))
        lights.append(L.area(rng, pos, (0, 0, 0.1), power=(30.0, 300.0), size=(0.2, 1.5)))
    if s.chance(rng, 0.35):  # a small bright source (bare bulb) near the props
        lights.append(L.point(rng, (rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6),
                                    rng.uniform(0.3, 1.0)), power=(5.0, 60.0), radius=(0.003, 0.02)))
    return {"objects": objects, "lights": lights,
            "world": L.world(rng, {"hdri": 3.0, "flat": 1.5, "dark": 0.5}),
            "rig": {"centre": [0.0, 0.0, 0.1], "distance": (0.6, 2.0), "height": (0.25, 1.2),
                    "lens": (28.0, 85.0),
                    "motions": {"static": 2, "orbit": 2, "dolly": 1.5, "shake": 1.5, "pan": 1,
                                "fast": 0.6}},
            "effects": {"dof": 0.45, "blur": 0.12, "move_light": 0.15, "switch_light": 0.15}}


def room_shell(rng, sx, sy, h, window):
    """Floor, ceiling and four walls (one with a window opening when ``window``).

    Returns (objects, window rectangle ``(x, z, width, height)`` in the +Y wall or ``None``).
    """
    wall = mats.material(rng, weights={"diffuse": 4, "textured": 1.5, "coated": 0.5})
    wall["base"] = [round(max(c, 0.15), 4) for c in wall["base"]]
    floor = mats.ground(rng, fine=s.chance(rng, 0.5))
    t = 0.1
    parts = [P.box((0, 0, -t / 2), (sx, sy, t), floor), P.box((0, 0, h + t / 2), (sx, sy, t), wall),
             P.box((-sx / 2 - t / 2, 0, h / 2), (t, sy, h), wall),
             P.box((sx / 2 + t / 2, 0, h / 2), (t, sy, h), wall),
             P.box((0, -sy / 2 - t / 2, h / 2), (sx, t, h), wall)]
    if not window:
        parts.append(P.box((0, sy / 2 + t / 2, h / 2), (sx, t, h), wall))
        return parts, None
    ww, wh = rng.uniform(1.0, min(2.5, sx - 1.0)), rng.uniform(0.8, h - 1.2)
    wx = rng.uniform(-(sx - ww) / 2 + 0.2, (sx - ww) / 2 - 0.2)
    wz = rng.uniform(0.8, h - 0.3 - wh) + wh / 2
    y = sy / 2 + t / 2
    left, right = wx - ww / 2 + sx / 2, sx / 2 - (wx + ww / 2)
    parts += [P.box((-sx / 2 + left / 2, y, h / 2), (left, t, h), wall),
              P.box((sx / 2 - right / 2, y, h / 2), (right, t, h), wall),
              P.box((wx, y, (wz - wh / 2) / 2), (ww, t, wz - wh / 2), wall),
              P.box((wx, y, (wz + wh / 2 + h) / 2), (ww, t, h - wz - wh / 2), wall)]
    if s.chance(rng, 0.5):  # window bars: thin geometry against the bright opening
        bars = mats.material(rng, rng.choice(["metal_rough", "diffuse"]))
        for k in range(1, rng.randint(2, 5)):
            x = wx - ww / 2 + ww * k / 5.0
            parts.append(P.obj("rod", (x, y, wz), (0, 0, wh), bars,
                               params={"radius": round(rng.uniform(0.005, 0.015), 4)}))
    return parts, (wx, wz, ww, wh)


def room(rng, frames):
    """A closed or windowed room: furniture, shelves of small objects, lamps (indirect light)."""
    sx, sy, h = rng.uniform(4.0, 8.0), rng.uniform(4.0, 8.0), rng.uniform(2.5, 3.4)
    window = s.chance(rng, 0.6)
    objects, opening = room_shell(rng, sx, sy, h, window)
    for x, y in P.scatter(rng, rng.randint(2, 5), min(sx, sy) / 2 - 0.8, min_gap=1.2):
        top = rng.uniform(0.4, 1.1)
        dims = (rng.uniform(0.5, 1.6), rng.uniform(0.4, 1.0), top)
        objects.append(P.box((x, y, top / 2), dims, mats.material(rng), rng.uniform(0, math.pi)))
        for _ in range(rng.randint(0, 3)):  # small things on the furniture
            o = P.prop(rng, (x + rng.uniform(-0.2, 0.2), y + rng.uniform(-0.15, 0.15), top),
                       s.log_uniform(rng, 0.03, 0.25))
            objects.append(o)
    if s.chance(rng, 0.5):  # a wall shelf with many small objects
        shelf_y, shelf_z = -sy / 2 + 0.2, rng.uniform(0.9, 1.8)
        objects.append(P.box((0, shelf_y, shelf_z), (min(2.5, sx - 1), 0.35, 0.03),
                             mats.material(rng, weights={"textured": 2, "coated": 1})))
        for k in range(rng.randint(5, 14)):
            x = rng.uniform(-min(1.2, sx / 2 - 0.6), min(1.2, sx / 2 - 0.6))
            objects.append(P.prop(rng, (x, shelf_y, shelf_z + 0.015), s.log_uniform(rng, 0.02, 0.2)))
    if s.chance(rng, 0.5):  # something moving through the room (a ball, a toy)
        o = P.prop(rng, (rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0), s.log_uniform(rng, 0.1, 0.4),
                   shape=rng.choice(["uv_sphere", "cube", "monkey", "torus"]))
        objects.append(P.make_moving(rng, o, s.log_uniform(rng, 0.02, 0.15), spin=0.1))
    lights = []
    if not window or s.chance(rng, 0.6):
        lights.append(L.area(rng, (rng.uniform(-1, 1), rng.uniform(-1, 1), h - 0.02),
                             (0, 0, 0), power=(100.0, 900.0), size=(0.4, 1.5)))
    for _ in range(rng.randint(0, 2)):  # lamps: small sources with a translucent shade
        x = rng.uniform(-sx / 2 + 0.5, sx / 2 - 0.5)
        y = rng.uniform(-sy / 2 + 0.5, sy / 2 - 0.5)
        z = rng.uniform(0.8, 2.0)
        lights.append(L.point(rng, (x, y, z), power=(20.0, 200.0), radius=(0.01, 0.06)))
        if s.chance(rng, 0.6):
            objects.append(P.obj("tube", (x, y, z + 0.05), (0.35, 0.35, 0.3),
                                 mats.material(rng, "translucent"), smooth=True))
    world = L.flat(rng, strength=(0.0, 0.05))
    if window:
        wx, wz, ww, wh = opening
        lights.append(L.portal((wx, sy / 2 + 0.06, wz), (wx, 0.0, wz), ww, wh))
        world = L.world(rng, {"sky": 2.0, "hdri": 2.0})
        if world["type"] == "sky":
            world["strength"] = round(rng.uniform(0.3, 1.0), 4)
        if s.chance(rng, 0.6):
            lights.append(L.sun(rng, aim=(0, 0, 0), strength=(2.0, 8.0), elevation=(15.0, 50.0)))
            sunl = lights[-1]
            sunl["location"] = s.vec(sunl["location"][0], abs(sunl["location"][1]) + 5.0,
                                     sunl["location"][2])  # through the +Y window side
    m = 0.35
    return {"objects": objects, "lights": lights, "world": world,
            "rig": {"centre": [rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 0.8],
                    "distance": (1.5, min(sx, sy) / 2 - 0.2), "height": (1.0, min(2.0, h - 0.4)),
                    "lens": (18.0, 40.0),
                    "bounds": [[-sx / 2 + m, -sy / 2 + m, 0.3], [sx / 2 - m, sy / 2 - m, h - m]],
                    "fast_track": False,
                    "motions": {"static": 1.5, "pan": 2, "dolly": 1.5, "shake": 1.5, "orbit": 1,
                                "fast": 0.5}},
            "effects": {"dof": 0.15, "blur": 0.1, "move_light": 0.1, "switch_light": 0.35}}


def showroom(rng, frames):
    """Pedestals with glass, metal and coated pieces, a glossy floor and often a mirror panel."""
    floor = mats.material(rng, rng.choice(["coated", "plastic", "textured"]))
    objects = [P.box((0, 0, -0.05), (12, 12, 0.1), floor)]
    back = mats.material(rng, weights={"diffuse": 3, "textured": 1})
    objects.append(P.box((0, 3.0, 2.0), (12, 0.1, 4.0), back))
    if s.chance(rng, 0.5):
        objects.append(P.box((rng.uniform(-2, 2), 2.9, 1.2), (rng.uniform(1.0, 2.5), 0.02, 1.8),
                             mats.material(rng, "metal_mirror")))
    showcase = {"glass": 2.0, "frosted_glass": 1.0, "metal_mirror": 1.5, "metal_rough": 1.5,
                "coated": 1.5, "translucent": 0.7, "plastic": 0.5}
    for x, y in P.scatter(rng, rng.randint(2, 5), 1.8, min_gap=0.9):
        ph = rng.uniform(0.4, 1.1)
        shape = rng.choice(["cube", "cylinder"])
        objects.append(P.obj(shape, (x, y, ph / 2), (0.5, 0.5, ph),
                             mats.material(rng, weights={"diffuse": 2, "coated": 1, "textured": 1}),
                             smooth=shape != "cube"))
        o = P.prop(rng, (x, y, ph), s.log_uniform(rng, 0.15, 0.45),
                   weights={"uv_sphere": 2, "monkey": 2, "torus": 1.5, "cube": 1, "ico_sphere": 1,
                            "helix": 0.5, "hair_ball": 0.3, "cone": 0.5},
                   material_weights=showcase)
        if s.chance(rng, 0.3):
            o["spin"] = s.vec(0, 0, rng.uniform(-0.1, 0.1))  # turntable
        objects.append(o)
    lights = [L.area(rng, (rng.uniform(-3, 3), rng.uniform(-3, 0), rng.uniform(2.0, 3.5)),
                     (0, 0, 0.5), power=(100.0, 1000.0), size=(0.5, 2.5))
              for _ in range(rng.randint(1, 2))]
    if s.chance(rng, 0.5):
        lights.append(L.spot(rng, (rng.uniform(-3, 3), rng.uniform(-3, 1), 3.5), (0, 0, 0.8)))
    return {"objects": objects, "lights": lights,
            "world": L.world(rng, {"hdri": 3.0, "flat": 1.0}),
            "rig": {"centre": [0.0, 0.0, 0.8], "distance": (2.0, 5.0), "height": (0.6, 2.2),
                    "lens": (24.0, 70.0),
                    "motions": {"orbit": 3, "dolly": 1.5, "static": 1, "shake": 1, "pan": 1,
                                "fast": 0.5}},
            "effects": {"dof": 0.3, "blur": 0.1, "move_light": 0.2, "switch_light": 0.1}}


def clutter(rng, frames):
    """A dense pile of many small objects of varied scale, wires and hair, seen from close up."""
    objects = [P.box((0, 0, -0.02), (6, 6, 0.04), mats.ground(rng, fine=s.chance(rng, 0.6)))]
    palette = [mats.material(rng) for _ in range(rng.randint(3, 8))]  # shared, like a kit of parts
    for x, y in P.scatter(rng, rng.randint(40, 110), 0.55, min_gap=0.03):
        size = s.log_uniform(rng, 0.01, 0.14)
        o = P.prop(rng, (x, y, 0.0), size, material=rng.choice(palette) if s.chance(rng, 0.6)
                   else None)
        objects.append(o)
    for _ in range(rng.randint(2, 8)):  # long thin wires across the pile
        objects.append(P.obj("rod", (rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4),
                                     rng.uniform(0.005, 0.12)), (0, 0, rng.uniform(0.4, 1.2)),
                             mats.material(rng, rng.choice(["metal_rough", "plastic", "diffuse"])),
                             rotation=(math.pi / 2 + rng.uniform(-0.2, 0.2), 0, rng.uniform(0, 6.3)),
                             params={"radius": round(s.log_uniform(rng, 0.0008, 0.004), 5)}))
    lights = [L.area(rng, s.on_circle((0, 0, 0), rng.uniform(0.8, 2.0), rng.uniform(0, 6.3),
                                      rng.uniform(0.8, 2.0)), (0, 0, 0), power=(20.0, 250.0),
                     size=(0.2, 1.2))]
    if s.chance(rng, 0.6):
        lights.append(L.point(rng, (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5),
                                    rng.uniform(0.3, 1.2)), power=(5.0, 80.0)))
    return {"objects": objects, "lights": lights,
            "world": L.world(rng, {"hdri": 2.0, "flat": 1.0, "sky": 0.5}),
            "rig": {"centre": [0.0, 0.0, 0.03], "distance": (0.35, 1.4), "height": (0.15, 1.0),
                    "lens": (30.0, 100.0),
                    "motions": {"orbit": 2, "shake": 2, "static": 1, "dolly": 1.5, "pan": 1,
                                "fast": 0.7},
                    "fast_track": False},
            "effects": {"dof": 0.5, "blur": 0.1, "move_light": 0.25, "switch_light": 0.1}}
