# SPDX-License-Identifier: Apache-2.0
"""Lighting that changes during a sequence: the events a denoiser's history must survive.

On top of the families' own moving and switching lights (``lighting.animate``), a scene gets one
lighting event with chance ``P_EVENT``, drawn after everything else so the rest of a description
does not depend on it. The events, after the paper's Sponza moving-light case and the shots users
make (lamps switched, flicker, fades, glowing screens):

* ``switch_off`` -- a light goes off at a frame after the first (sometimes back on later);
* ``switch_on`` -- a light that was off comes on;
* ``move_fast`` -- a light moves 0.15-0.6 m per frame, so its shadows sweep;
* ``flicker`` -- a light's power jumps to a random factor (0.05-1.4) at every frame;
* ``fade`` -- a light's power ramps linearly to a factor 0-0.3 (or from it) over a few frames;
* ``emission`` -- an object's emission strength switches or ramps (screens, neon, lava).

A scene without a movable light gets one near the camera's target. Light fields: ``fade`` is
``None`` or ``[[frame, power_factor], ...]`` keyed linearly; materials may carry
``emission_keys`` ``[[frame, strength], ...]`` with ``emission_interp`` ``"CONSTANT"`` or
``"LINEAR"``.
"""

from . import lighting as L
from . import sampling as s

P_EVENT = 0.65
EVENTS = {"switch_off": 3.0, "switch_on": 2.0, "move_fast": 2.0, "flicker": 1.5, "fade": 1.5,
          "emission": 2.0}


def _movable(lights):
    return [lt for lt in lights if lt["type"] != "SUN" and not lt.get("portal")]


def _new_light(rng, camera):
    """A point or area light 1.5-3 m above and beside the camera's first target."""
    t = camera["keys"][0]["target"]
    loc = (t[0] + rng.uniform(-2.5, 2.5), t[1] + rng.uniform(-2.5, 2.5), t[2] + rng.uniform(1.5, 3.0))
    if s.chance(rng, 0.5):
        return L.point(rng, loc, power=(100.0, 600.0))
    return L.area(rng, loc, t, power=(150.0, 900.0), size=(0.2, 1.2))


def _event_frames(rng, frames):
    """First frame of an event: late enough for a history to exist, early enough to be seen."""
    return rng.randint(min(2, frames - 1), max(min(2, frames - 1), frames - 3))


def _light_event(rng, kind, lt, frames):
    f = _event_frames(rng, frames)
    if kind == "switch_off":
        lt["switch"] = [[f, 0.0, lt["colour"]]]
        if f + 2 < frames and s.chance(rng, 0.3):
            lt["switch"].append([f + 2, 1.0, lt["colour"]])
    elif kind == "switch_on":
        lt["switch"] = [[0, 0.0, lt["colour"]], [f, 1.0, lt["colour"]]]
    elif kind == "move_fast":
        L.make_moving(rng, lt, rng.uniform(0.15, 0.6))
    elif kind == "flicker":
        lt["switch"] = [[k, round(rng.uniform(0.05, 1.4), 3), lt["colour"]] for k in range(1, frames)]
    elif kind == "fade":
        end = min(frames - 1, f + rng.randint(1, 3))
        low = round(rng.uniform(0.0, 0.3), 3)
        lt["fade"] = [[f - 1, 1.0], [end, low]] if s.chance(rng, 0.6) else [[f - 1, low], [end, 1.0]]


def _emission_event(rng, objects, frames):
    """Animate one object's emission; prefer objects that already glow."""
    glowing = [o for o in objects if o["material"]["emission_strength"] > 0]
    pool = glowing or [o for o in objects if o["material"]["transmission"] == 0]
    if not pool:
        return False
    o = rng.choice(pool)
    m = dict(o["material"])
    peak = m["emission_strength"] or round(s.log_uniform(rng, 2.0, 20.0), 3)
    if not any(m["emission"]):
        m["emission"] = s.colour(rng, sat=(0.0, 0.9), val=(0.8, 1.0))
    f = _event_frames(rng, frames)
    if s.chance(rng, 0.5):
        on_first = s.chance(rng, 0.5)
        m["emission_keys"] = [[0, peak if on_first else 0.0], [f, 0.0 if on_first else peak]]
        m["emission_interp"] = "CONSTANT"
    else:
        m["emission_keys"] = [[0, peak], [f, peak], [min(frames - 1, f + 2), round(peak * 0.05, 4)]]
        m["emission_interp"] = "LINEAR"
    m["emission_strength"] = m["emission_keys"][0][1]
    o["material"] = m
    return True


def add_event(rng, lights, objects, camera, frames, p_event=P_EVENT):
    """Maybe add one lighting event to the description's ``lights``/``objects``; return its kind."""
    if frames < 3 or not s.chance(rng, p_event):
        return None
    kind = s.pick(rng, EVENTS)
    if kind == "emission" and _emission_event(rng, objects, frames):
        return kind
    if kind == "emission":
        kind = "switch_off"
    pool = [lt for lt in _movable(lights) if not lt["switch"] and not any(lt["velocity"])]
    if not pool:
        lights.append(_new_light(rng, camera))
        pool = [lights[-1]]
    _light_event(rng, kind, rng.choice(pool), frames)
    return kind
