# SPDX-License-Identifier: Apache-2.0
"""Worlds and lights of the scene generator: JSON descriptions, drawn from a ``random.Random``.

World (``type``): ``sky`` (Nishita sky, optional sun disc), ``hdri`` (one of the environment maps
that ship with Blender, :data:`HDRIS`), ``flat`` (uniform colour, may be black).

Light: ``type`` AREA/POINT/SPOT/SUN, ``power`` (watts; SUN: W/m^2), ``colour``, ``size`` (AREA edge,
POINT/SPOT radius in metres, SUN angular diameter in degrees), ``location`` at frame 0, ``aim``
(point the light faces, or ``None``), ``velocity`` (metres per frame, constant), ``spot_deg``
(SPOT cone), ``portal`` (AREA light that is a light portal for the world, ``size`` by ``size_y``,
never moved or switched), ``switch`` (``None`` or a list of ``[frame, power_factor, colour]``
steps: the light jumps to ``power * power_factor`` and ``colour`` at that frame), ``fade``
(``None`` or ``[[frame, power_factor], ...]`` keyed linearly; see ``lighting_change``).
"""

import math

from . import sampling as s

# Environment maps installed with Blender (datafiles/studiolights/world, 1024x512 EXR).
HDRIS = ("city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset")


def sky(rng, strength=(0.1, 0.6), elevation=(4.0, 70.0), sun_disc=0.6):
    """Nishita sky; ``elevation`` range of the sun in degrees; sun disc with chance ``sun_disc``."""
    return {"type": "sky", "strength": round(rng.uniform(*strength), 4),
            "sun_elevation": round(rng.uniform(*elevation), 3),
            "sun_rotation": round(rng.uniform(0.0, 360.0), 3), "sun_disc": s.chance(rng, sun_disc)}


def hdri(rng, strength=(0.3, 2.0), names=HDRIS):
    """One of Blender's bundled environment maps, rotated about Z by a random angle."""
    return {"type": "hdri", "name": rng.choice(list(names)),
            "strength": round(s.log_uniform(rng, *strength), 4),
            "rotation": round(rng.uniform(0.0, 360.0), 3)}


def flat(rng, strength=(0.0, 0.3), colour=None):
    """Uniform world colour (ambient); strength 0 gives a black world."""
    return {"type": "flat", "colour": colour or s.colour(rng, sat=(0.0, 0.5), val=(0.3, 1.0)),
            "strength": round(rng.uniform(*strength), 4)}


def world(rng, weights, hdri_names=HDRIS):
    """Draw a world type from ``weights`` (``sky``/``hdri``/``flat``/``dark`` -> weight)."""
    kind = s.pick(rng, weights)
    if kind == "sky":
        return sky(rng)
    if kind == "hdri":
        return hdri(rng, names=hdri_names)
    if kind == "dark":
        return flat(rng, strength=(0.0, 0.01))
    return flat(rng)


def light(kind, location, power, colour=(1.0, 1.0, 1.0), size=0.1, aim=None, spot_deg=45.0):
    """A static light description (see the module docstring for the fields)."""
    return {"type": kind, "power": round(float(power), 4), "colour": [round(c, 4) for c in colour],
            "size": round(float(size), 5), "location": s.vec(*location),
            "aim": None if aim is None else s.vec(*aim), "velocity": [0.0, 0.0, 0.0],
            "spot_deg": round(float(spot_deg), 3), "switch": None, "fade": None}


def portal(location, aim, width, height):
    """Light portal (an AREA light that only guides sampling of the world) over a window."""
    lt = light("AREA", location, 0.0, size=width, aim=aim)
    lt.update(portal=True, size_y=round(float(height), 5))
    return lt


def area(rng, location, aim, power=(100.0, 800.0), size=(0.3, 2.5), tint=0.25):
    """Soft area light facing ``aim``; power and size drawn log-uniformly."""
    return light("AREA", location, s.log_uniform(rng, *power), s.warm_white(rng, tint),
                 s.log_uniform(rng, *size), aim)


def point(rng, location, power=(20.0, 400.0), radius=(0.005, 0.2), coloured=0.3):
    """Point light; a small radius makes a small bright source with hard shadows."""
    col = s.colour(rng, sat=(0.3, 1.0), val=(0.9, 1.0)) if s.chance(rng, coloured) \
        else s.warm_white(rng)
    return light("POINT", location, s.log_uniform(rng, *power), col, s.log_uniform(rng, *radius))


def spot(rng, location, aim, power=(200.0, 2000.0), cone=(20.0, 70.0)):
    """Spot light aimed at ``aim``."""
    return light("SPOT", location, s.log_uniform(rng, *power), s.warm_white(rng),
                 s.log_uniform(rng, 0.01, 0.2), aim, rng.uniform(*cone))


def sun(rng, aim=(0.0, 0.0, 0.0), strength=(1.0, 6.0), angle=(0.3, 6.0), elevation=(10.0, 70.0)):
    """Sun light from a random direction (``elevation`` degrees above the horizon)."""
    el, az = math.radians(rng.uniform(*elevation)), rng.uniform(0.0, 2.0 * math.pi)
    d = 20.0
    loc = (aim[0] + d * math.cos(el) * math.cos(az), aim[1] + d * math.cos(el) * math.sin(az),
           aim[2] + d * math.sin(el))
    return light("SUN", loc, rng.uniform(*strength), s.warm_white(rng, 0.15),
                 s.log_uniform(rng, *angle), aim)


def make_moving(rng, lt, speed):
    """Give ``lt`` a constant velocity of ``speed`` metres per frame (mostly horizontal)."""
    lt["velocity"] = s.linear_motion(rng, speed, vertical=speed * 0.3)
    return lt


def make_switching(rng, lt, frames, colour_change=0.5):
    """Switch ``lt`` off/on or to other colours at 1-3 random frames after the first."""
    if frames < 2:
        return lt
    steps = sorted(rng.sample(range(1, frames), min(frames - 1, rng.randint(1, 3))))
    on = True
    lt["switch"] = []
    for f in steps:
        if s.chance(rng, colour_change):
            col = s.colour(rng, sat=(0.4, 1.0), val=(0.9, 1.0))
            lt["switch"].append([f, round(rng.uniform(0.5, 2.0), 3), col])
        else:
            on = not on
            lt["switch"].append([f, 1.0 if on else 0.0, lt["colour"]])
    return lt


def animate(rng, lights, frames, p_move=0.2, p_switch=0.15, speed=(0.03, 0.3)):
    """Make some of ``lights`` (not suns) move or switch; return how many were animated."""
    count = 0
    for lt in lights:
        if lt["type"] == "SUN" or lt.get("portal"):
            continue
        if s.chance(rng, p_move):
            make_moving(rng, lt, s.log_uniform(rng, *speed))
            count += 1
        elif s.chance(rng, p_switch):
            make_switching(rng, lt, frames)
            count += 1
    return count
