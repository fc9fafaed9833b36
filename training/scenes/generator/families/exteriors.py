# SPDX-License-Identifier: Apache-2.0
"""Outdoor and abstract scene families: ``outdoor``, ``night``, ``kinetic`` and ``atrium``.

``atrium`` is the family held out of training entirely (``split.py``). Each ``layout(rng, frames)``
returns the same fields as the indoor families (``interiors.py``).
"""

import math

from .. import lighting as L
from .. import materials as mats
from .. import sampling as s
from . import props as P


def tree(rng, x, y):
    """A trunk and one or two canopy blobs (translucent or diffuse foliage)."""
    h = rng.uniform(1.5, 4.0)
    bark = mats.material(rng, "textured")
    bark["base"] = s.colour(rng, sat=(0.3, 0.6), val=(0.15, 0.35))
    leaves = mats.material(rng, rng.choice(["translucent", "diffuse", "textured"]))
    leaves["base"] = s.colour(rng, sat=(0.4, 0.9), val=(0.2, 0.6))
    r = rng.uniform(0.06, 0.2)
    parts = [P.obj("cylinder", (x, y, h / 2), (2 * r, 2 * r, h), bark)]
    for _ in range(rng.randint(1, 2)):
        c = rng.uniform(0.6, 1.6)
        parts.append(P.obj("rock", (x + rng.uniform(-0.3, 0.3), y + rng.uniform(-0.3, 0.3),
                                    h + c * 0.3), (c, c, c * 0.9), leaves,
                           params={"noise_scale": round(rng.uniform(1.0, 3.0), 3),
                                   "seed": rng.randrange(1 << 16)}))
    return parts


def outdoor(rng, frames):
    """A field under sky or an environment map: grass, rocks, trees, fences, posts, moving things."""
    objects = [P.obj("plane", (0, 0, 0), (80, 80, 0), mats.ground(rng), smooth=False)]
    for x, y in P.scatter(rng, rng.randint(0, 3), 6.0, min_gap=2.5):  # patches of grass
        size = rng.uniform(1.5, 4.0)
        o = P.prop(rng, (x, y, 0.0), size, shape="grass")
        o["dims"] = s.vec(size, size, 0.0)
        o["location"][2] = 0.0
        o["material"] = mats.ground(rng)
        objects.append(o)
    for x, y in P.scatter(rng, rng.randint(0, 5), 9.0, min_gap=2.0, avoid=(0, 0, 1.5)):
        objects.extend(tree(rng, x, y))
    if s.chance(rng, 0.6):  # a fence of thin posts and wire mesh
        n, gap, yaw = rng.randint(5, 14), rng.uniform(0.4, 1.2), rng.uniform(0, math.pi)
        x0, y0 = rng.uniform(-4, 4), rng.uniform(-4, 4)
        post = mats.material(rng, rng.choice(["metal_rough", "diffuse", "textured"]))
        for k in range(n):
            x, y = x0 + k * gap * math.cos(yaw), y0 + k * gap * math.sin(yaw)
            objects.append(P.obj("rod", (x, y, 0.6), (0, 0, 1.2), post,
                                 params={"radius": round(rng.uniform(0.01, 0.04), 4)}))
        if s.chance(rng, 0.6):
            length = (n - 1) * gap
            objects.append(P.obj("wire_grid", (x0 + length / 2 * math.cos(yaw),
                                               y0 + length / 2 * math.sin(yaw), 0.55),
                                 (length, 1.0, 0), mats.material(rng, "metal_rough"),
                                 rotation=(math.pi / 2, 0, yaw), smooth=False,
                                 params={"cuts": rng.randint(10, 40),
                                         "thickness": round(rng.uniform(0.002, 0.006), 4)}))
    for x, y in P.scatter(rng, rng.randint(4, 12), 7.0, min_gap=0.8, avoid=(0, 0, 1.0)):
        o = P.prop(rng, (x, y, 0.0), s.log_uniform(rng, 0.15, 1.5))
        if s.chance(rng, 0.3):
            P.make_moving(rng, o, s.log_uniform(rng, 0.03, 0.4), spin=0.12)
        objects.append(o)
    world = L.world(rng, {"sky": 3.0, "hdri": 2.0})
    lights = []
    if world["type"] == "hdri" or not world["sun_disc"] or s.chance(rng, 0.3):
        lights.append(L.sun(rng, strength=(1.0, 5.0)))
    return {"objects": objects, "lights": lights, "world": world,
            "rig": {"centre": [0.0, 0.0, 0.8], "distance": (3.0, 10.0), "height": (0.8, 4.0),
                    "lens": (18.0, 55.0),
                    "motions": {"fast": 2, "pan": 1.5, "orbit": 1, "dolly": 1, "shake": 1,
                                "static": 0.5}},
            "effects": {"dof": 0.15, "blur": 0.15, "move_light": 0.0, "switch_light": 0.0}}


def night(rng, frames):
    """A street at night: wet road, buildings with lit windows, neon tubes, street lamps, cars."""
    road = mats.material(rng, "coated")
    road["base"] = s.colour(rng, sat=(0.0, 0.2), val=(0.05, 0.2))
    objects = [P.obj("plane", (0, 0, 0), (60, 60, 0), road, smooth=False)]
    width = rng.uniform(6.0, 12.0)
    for side in (-1, 1):
        x = 0.0
        y = side * (width / 2 + rng.uniform(2.0, 4.0))
        while x < 30.0:
            bw, bh, bd = rng.uniform(3, 8), rng.uniform(4, 15), rng.uniform(3, 6)
            facade = mats.material(rng, weights={"textured": 2, "diffuse": 2, "coated": 1})
            objects.append(P.box((x - 15 + bw / 2, y + side * bd / 2, bh / 2), (bw, bd, bh), facade))
            glow = mats.emissive(rng, (0.5, 8.0), s.warm_white(rng, 0.4))
            for _ in range(rng.randint(2, 8)):  # lit windows
                wx = x - 15 + rng.uniform(0.5, bw - 0.5)
                wz = rng.uniform(1.0, bh - 1.0)
                objects.append(P.box((wx, y - side * 0.01, wz), (0.6, 0.02, 0.9), glow))
            x += bw + rng.uniform(0.0, 1.5)
    for _ in range(rng.randint(2, 6)):  # neon tubes on the facades
        side = rng.choice((-1, 1))
        tube = mats.emissive(rng, (5.0, 40.0))
        objects.append(P.obj("rod", (rng.uniform(-12, 12), side * (width / 2 + 1.9),
                                     rng.uniform(2.0, 5.0)), (0, 0, rng.uniform(0.8, 3.0)), tube,
                             rotation=(0, math.pi / 2 * rng.choice((0, 1)), 0),
                             params={"radius": round(rng.uniform(0.015, 0.04), 4)}))
    lights = []
    pole = mats.material(rng, "metal_rough")
    for k in range(rng.randint(2, 5)):  # street lamps: thin pole + small bright source
        x, side = rng.uniform(-12, 12), rng.choice((-1, 1))
        y = side * (width / 2 + 0.5)
        objects.append(P.obj("rod", (x, y, 2.5), (0, 0, 5.0), pole, params={"radius": 0.05}))
        lights.append(L.point(rng, (x, y, 5.1), power=(400.0, 3000.0), radius=(0.02, 0.1),
                              coloured=0.4))
    for _ in range(rng.randint(1, 4)):  # cars: glossy boxes with headlights, driving along x
        car = P.box((rng.uniform(-10, 10), rng.uniform(-width / 2 + 1, width / 2 - 1), 0.7),
                    (rng.uniform(3.5, 4.8), 1.8, 1.3), mats.material(rng, "coated"))
        P.make_moving(rng, car, 0.0)
        car["velocity"] = s.vec(rng.choice((-1, 1)) * rng.uniform(0.1, 0.6), 0, 0)
        objects.append(car)
        head = dict(car, material=mats.emissive(rng, (10.0, 60.0), (1.0, 0.95, 0.8)), spin=[0, 0, 0])
        head["location"] = s.vec(car["location"][0] + math.copysign(car["dims"][0] / 2 + 0.02,
                                                                    car["velocity"][0]),
                                 car["location"][1], 0.6)
        head["dims"] = s.vec(0.04, 1.5, 0.15)
        objects.append(head)
    return {"objects": objects, "lights": lights,
            "world": L.world(rng, {"dark": 2.0, "hdri": 1.0}, hdri_names=("night",)),
            "rig": {"centre": [0.0, 0.0, 1.5], "distance": (5.0, 12.0), "height": (1.2, 5.0),
                    "lens": (20.0, 50.0),
                    "bounds": [[-25.0, -width / 2 + 0.5, 0.5], [25.0, width / 2 - 0.5, 6.0]],
                    "motions": {"dolly": 1.5, "fast": 1.5, "pan": 1.5, "static": 1, "shake": 1,
                                "orbit": 0.5}},
            "effects": {"dof": 0.15, "blur": 0.2, "move_light": 0.15, "switch_light": 0.35}}


def kinetic(rng, frames):
    """Objects flying and tumbling fast through an open space; moving lights; often motion blur."""
    objects = []
    if s.chance(rng, 0.7):
        objects.append(P.obj("plane", (0, 0, 0), (60, 60, 0), mats.ground(rng), smooth=False))
    for x, y in P.scatter(rng, rng.randint(8, 20), 5.0, min_gap=0.6, avoid=(0, 0, 0.5)):
        o = P.prop(rng, (x, y, rng.uniform(0.0, 2.5)), s.log_uniform(rng, 0.1, 1.0))
        if s.chance(rng, 0.7):
            P.make_moving(rng, o, s.log_uniform(rng, 0.05, 0.5), spin=0.3, vertical=0.1)
        objects.append(o)
    lights = [L.area(rng, (rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(3, 6)), (0, 0, 1),
                     power=(300.0, 2500.0), size=(0.5, 3.0))]
    for _ in range(rng.randint(0, 3)):
        lights.append(L.point(rng, (rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(0.5, 3)),
                              power=(50.0, 600.0), coloured=0.6))
    if s.chance(rng, 0.4):
        lights.append(L.sun(rng))
    return {"objects": objects, "lights": lights,
            "world": L.world(rng, {"sky": 1.0, "hdri": 2.0, "flat": 1.0, "dark": 0.5}),
            "rig": {"centre": [0.0, 0.0, 1.2], "distance": (4.0, 9.0), "height": (0.8, 4.0),
                    "lens": (20.0, 50.0),
                    "motions": {"fast": 2, "orbit": 1.5, "pan": 1, "shake": 1, "static": 1,
                                "dolly": 0.5}},
            "effects": {"dof": 0.15, "blur": 0.35, "move_light": 0.5, "switch_light": 0.15}}


def atrium(rng, frames):
    """A courtyard open to the sky: colonnade, tiled floor, a glassy pool, plants, a statue."""
    half = rng.uniform(4.0, 7.0)
    h = rng.uniform(3.0, 6.0)
    floor = mats.ground(rng, fine=True)
    wall = mats.material(rng, weights={"diffuse": 2, "textured": 2})
    objects = [P.box((0, 0, -0.05), (2 * half + 1, 2 * half + 1, 0.1), floor)]
    for k in range(4):  # walls around, open roof
        a = k * math.pi / 2
        objects.append(P.box((half * math.cos(a), half * math.sin(a), h / 2),
                             (0.3, 2 * half + 0.3, h), wall, yaw=a))
    column = mats.material(rng, weights={"diffuse": 2, "textured": 1, "coated": 1})
    n = rng.randint(3, 7)
    for side in range(4):
        a = side * math.pi / 2
        for k in range(n):
            t = -half + 1.0 + k * (2 * half - 2.0) / max(1, n - 1)
            x, y = (half - 1.0) * math.cos(a) - t * math.sin(a), (half - 1.0) * math.sin(a) + \
                t * math.cos(a)
            objects.append(P.obj("cylinder", (x, y, h / 2), (0.25, 0.25, h), column))
    if s.chance(rng, 0.8):  # pool: a transmissive water surface over a tiled basin
        pw, pd = rng.uniform(1.5, 3.0), rng.uniform(1.0, 2.5)
        objects.append(P.box((0, 0, 0.02), (pw + 0.3, pd + 0.3, 0.04),
                             mats.material(rng, "textured")))
        water = mats.material(rng, rng.choice(["glass", "frosted_glass"]))
        water["ior"] = 1.33
        objects.append(P.obj("plane", (0, 0, 0.05), (pw, pd, 0), water, smooth=False))
    for x, y in P.scatter(rng, rng.randint(1, 4), half - 2.0, min_gap=1.5, avoid=(0, 0, 1.8)):
        o = P.prop(rng, (x, y, 0.0), rng.uniform(0.6, 1.4), shape="grass")
        o["dims"], o["location"][2] = s.vec(1.0, 1.0, 0.0), 0.0
        objects.append(o)
    statue = P.prop(rng, (rng.uniform(-1, 1), rng.uniform(-1, 1), 0.4), rng.uniform(0.6, 1.2),
                    shape="monkey", material=mats.material(rng, rng.choice(["metal_rough",
                                                                             "metal_mirror",
                                                                             "coated"])))
    objects.append(P.box((statue["location"][0], statue["location"][1], 0.2), (0.7, 0.7, 0.4),
                         column))
    objects.append(statue)
    if s.chance(rng, 0.5):  # a bird or a ball passing through
        o = P.prop(rng, (rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(0.5, 2.5)), 0.25,
                   shape=rng.choice(["uv_sphere", "torus", "cube"]))
        objects.append(P.make_moving(rng, o, rng.uniform(0.05, 0.3), spin=0.2))
    world = L.world(rng, {"sky": 1.0, "hdri": 1.0})
    lights = [L.sun(rng, strength=(2.0, 6.0), elevation=(35.0, 80.0))] if s.chance(rng, 0.7) else []
    return {"objects": objects, "lights": lights, "world": world,
            "rig": {"centre": [0.0, 0.0, 1.0], "distance": (2.0, half - 0.8), "height": (1.0, 3.0),
                    "lens": (18.0, 40.0), "fast_track": False,
                    "bounds": [[-half + 0.5, -half + 0.5, 0.3], [half - 0.5, half - 0.5, h]],
                    "motions": {"orbit": 2, "dolly": 1.5, "pan": 1.5, "shake": 1, "static": 1,
                                "fast": 0.5}},
            "effects": {"dof": 0.2, "blur": 0.15, "move_light": 0.0, "switch_light": 0.0}}
