# SPDX-License-Identifier: Apache-2.0
"""Small random-draw and vector helpers shared by the pure-Python generator modules.

Every draw goes through a ``random.Random`` passed in by the caller, so a description depends only
on the generator's seed. Colours are linear RGB in 0..1; vectors are 3-lists in metres.
"""

import colorsys
import math


def pick(rng, weights):
    """Draw a key of ``weights`` (key -> relative weight), in the dict's order."""
    total = float(sum(weights.values()))
    x = rng.uniform(0.0, total)
    for key, weight in weights.items():
        x -= weight
        if x <= 0.0:
            return key
    return list(weights)[-1]


def chance(rng, p):
    """True with probability ``p``."""
    return rng.random() < p


def log_uniform(rng, lo, hi):
    """Draw from ``lo``..``hi`` uniformly in log space (scales, powers, texture frequencies)."""
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def colour(rng, sat=(0.0, 0.9), val=(0.05, 0.9)):
    """A linear-RGB colour: uniform hue, saturation and (sRGB-like) value from the ranges."""
    r, g, b = colorsys.hsv_to_rgb(rng.random(), rng.uniform(*sat), rng.uniform(*val))
    return [round(c ** 2.2, 4) for c in (r, g, b)]


def warm_white(rng, spread=0.25):
    """A light colour between warm (tungsten-like) and cool white; ``spread`` 0 gives pure white."""
    t = rng.uniform(-spread, spread)
    return [round(min(1.0, 1.0 + t), 4), round(1.0 - abs(t) * 0.3, 4), round(min(1.0, 1.0 - t), 4)]


def vec(*xs):
    """A 3-list rounded to 5 decimals (keeps descriptions stable and readable)."""
    return [round(float(x), 5) for x in xs]


def add(a, b):
    return vec(*(x + y for x, y in zip(a, b)))


def sub(a, b):
    return vec(*(x - y for x, y in zip(a, b)))


def scale(a, s):
    return vec(*(x * s for x in a))


def length(a):
    return math.sqrt(sum(x * x for x in a))


def normalise(a):
    n = length(a)
    return vec(*(x / n for x in a)) if n > 0 else vec(0, 0, 0)


def on_circle(centre, radius, angle, z):
    """Point at ``angle`` radians on a horizontal circle around ``centre`` at height ``z``."""
    return vec(centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle), z)


def linear_motion(rng, speed, vertical=0.0):
    """A random horizontal velocity of magnitude ``speed`` (m/frame), optional vertical part."""
    a = rng.uniform(0.0, 2.0 * math.pi)
    return vec(speed * math.cos(a), speed * math.sin(a), rng.uniform(-vertical, vertical))
