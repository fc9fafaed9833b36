# SPDX-License-Identifier: Apache-2.0
"""Camera paths of the scene generator: JSON descriptions with one key per frame (no ``bpy``).

A camera is ``lens`` (mm, 36 mm sensor width), ``motion`` (one of :data:`MOTIONS`), ``keys`` (one
``{"location", "target"}`` per frame; Blender interpolates linearly between them, so the Vector
pass sees piecewise-constant velocity) and ``dof`` (``None`` or ``{"fstop", "focus_distance"}``).

A family describes where the camera may go with a rig dict: ``centre`` (point looked at),
``distance`` and ``height`` ranges (metres from ``centre``; height above the floor), ``lens`` range,
``motions`` (kind -> weight), optional ``bounds`` (``[[xmin, ymin, zmin], [xmax, ymax, zmax]]``:
camera positions are clamped into it, e.g. the inside of a room) and optional ``fast_track``
(``False``: fast motion is a fast orbit, never a straight track that could leave a room).
"""

import math

from . import sampling as s

MOTIONS = ("static", "pan", "orbit", "dolly", "shake", "fast")

# Speed ranges per motion: degrees per frame (pan, orbit) or metres per frame (dolly, fast track).
PAN_DEG = (0.3, 2.0)
ORBIT_DEG = (0.3, 3.0)
DOLLY_FRACTION = (0.005, 0.03)      # of the camera distance, per frame
SHAKE_M = (0.004, 0.03)             # standard deviation of hand-held position jitter
FAST_TRACK_M = (0.25, 0.8)
FAST_ORBIT_DEG = (4.0, 10.0)


def _jitter(rng, sigma):
    return s.vec(rng.gauss(0, sigma), rng.gauss(0, sigma), rng.gauss(0, sigma * 0.6))


def path(rng, rig, frames, motion):
    """Per-frame ``{"location", "target"}`` keys for ``motion`` around the family's ``rig``."""
    centre = rig["centre"]
    dist = rng.uniform(*rig["distance"])
    height = rng.uniform(*rig["height"])
    angle = rng.uniform(0.0, 2.0 * math.pi)
    horiz = math.sqrt(max(dist * dist - (height - centre[2]) ** 2, (0.3 * dist) ** 2))
    eye = s.on_circle(centre, horiz, angle, height)
    target = s.add(centre, _jitter(rng, 0.15 * dist))
    keys = []
    fast_orbit = motion == "fast" and (not rig.get("fast_track", True) or s.chance(rng, 0.4))
    if motion == "orbit" or fast_orbit:
        rate = math.radians(rng.uniform(*(FAST_ORBIT_DEG if motion == "fast" else ORBIT_DEG)))
        rate *= rng.choice((-1, 1))
        for f in range(frames):
            keys.append({"location": s.on_circle(centre, horiz, angle + rate * f, height),
                         "target": target})
        return keys
    if motion == "pan":
        rate = math.radians(rng.uniform(*PAN_DEG)) * rng.choice((-1, 1))
        look = s.sub(target, eye)
        yaw0, r = math.atan2(look[1], look[0]), math.hypot(look[0], look[1])
        for f in range(frames):
            a = yaw0 + rate * (f - (frames - 1) / 2.0)
            keys.append({"location": eye, "target": s.vec(eye[0] + r * math.cos(a),
                                                          eye[1] + r * math.sin(a), target[2])})
        return keys
    if motion == "dolly":
        step = s.scale(s.sub(target, eye), rng.uniform(*DOLLY_FRACTION) * rng.choice((-1, 1)))
        start = s.sub(eye, s.scale(step, (frames - 1) / 2.0))
        for f in range(frames):
            keys.append({"location": s.add(start, s.scale(step, f)), "target": target})
        return keys
    if motion == "fast":
        speed = rng.uniform(*FAST_TRACK_M)
        look = s.normalise(s.sub(target, eye))
        side = s.normalise([-look[1], look[0], 0.0])
        mix = rng.uniform(0.0, 1.0)
        direction = s.normalise(s.add(s.scale(side, 1.0 - mix), s.scale([look[0], look[1], 0], mix)))
        step = s.scale(direction, speed * rng.choice((-1, 1)))
        half = s.scale(step, (frames - 1) / 2.0)
        for f in range(frames):
            shift = s.sub(s.scale(step, f), half)
            keys.append({"location": s.add(eye, shift), "target": s.add(target, shift)})
        return keys
    if motion == "shake":
        sigma = s.log_uniform(rng, *SHAKE_M)
        drift = s.scale(s.linear_motion(rng, 1.0), rng.uniform(0.0, 0.02))
        for f in range(frames):
            keys.append({"location": s.add(s.add(eye, s.scale(drift, f)), _jitter(rng, sigma)),
                         "target": s.add(target, _jitter(rng, sigma * 2.0))})
        return keys
    if motion == "static":
        return [{"location": eye, "target": target} for _ in range(frames)]
    raise ValueError("unknown camera motion %r" % motion)


def camera(rng, rig, frames, p_dof=0.25, blocked=None, tries=30):
    """Draw a camera for ``rig``: motion kind, per-frame keys, lens and (sometimes) depth of field.

    ``blocked(point)`` says whether a camera position lies inside scene geometry; paths with such a
    position are drawn again (up to ``tries`` times, then the last one is kept).
    """
    motion = s.pick(rng, rig["motions"])
    for _ in range(tries):
        keys = path(rng, rig, frames, motion)
        if rig.get("bounds"):
            lo, hi = rig["bounds"]
            for k in keys:
                k["location"] = s.vec(*(min(max(x, a), b)
                                        for x, a, b in zip(k["location"], lo, hi)))
        if blocked is None or not any(blocked(k["location"]) for k in keys):
            break
    lens = s.log_uniform(rng, *rig["lens"])
    dof = None
    if s.chance(rng, p_dof):
        mid = keys[len(keys) // 2]
        focus = s.length(s.sub(mid["target"], mid["location"])) * rng.uniform(0.6, 1.2)
        dof = {"fstop": round(s.log_uniform(rng, 0.7, 4.0), 3), "focus_distance": round(focus, 4)}
    return {"lens": round(lens, 3), "sensor_width": 36.0, "motion": motion, "keys": keys,
            "dof": dof}


def speed_px(cam, width=256):
    """Rough largest per-frame image motion of the camera, in pixels at ``width`` (manifest)."""
    keys = cam["keys"]
    if len(keys) < 2:
        return 0.0
    worst = 0.0
    fov = 2.0 * math.atan(cam["sensor_width"] / (2.0 * cam["lens"]))
    for a, b in zip(keys, keys[1:]):
        da = s.normalise(s.sub(a["target"], a["location"]))
        db = s.normalise(s.sub(b["target"], b["location"]))
        turn = math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(da, db)))))
        dist = max(0.1, s.length(s.sub(a["target"], a["location"])))
        move = s.length(s.sub(b["location"], a["location"])) / dist
        worst = max(worst, (turn + move) / fov * width)
    return round(worst, 2)
