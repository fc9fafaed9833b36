# SPDX-License-Identifier: Apache-2.0
"""Turn a (family, seed) pair into a complete JSON scene description (no ``bpy``).

The description holds everything Blender needs (``blender_build.py``): world, lights, objects,
camera keys, depth of field, motion blur, the exposure target and the path-tracing settings. It is
a pure function of (family, seed, frames): the random generator is seeded with the string
``afn-scene:<family>:<seed>`` (Python hashes string seeds with SHA-512, so the draws do not depend
on the interpreter's hash randomisation).

Usage: /usr/bin/python3 -m generator.describe FAMILY SEED [FRAMES]   (from training/scenes)
"""

import json
import random
import sys

from . import camera as cam
from . import lighting as L
from . import lighting_change
from . import sampling as s
from . import surfaces
from .families import FAMILIES
from .families.props import inside

FORMAT = "afn-scene-3"

# Path-tracing settings shared by every generated scene (inputs and references alike).
RENDER = {"max_bounces": 8, "diffuse_bounces": 3, "glossy_bounces": 4,
          "transmission_bounces": 8, "transparent_max_bounces": 8}


def summary(desc):
    """What a description contains, for the manifest and for coverage checks."""
    objs, camera = desc["objects"], desc["camera"]
    lights = [lt for lt in desc["lights"] if not lt.get("portal")]
    kinds = sorted({o["material"]["kind"] for o in objs})
    shapes = sorted({o["shape"] for o in objs})
    return {
        "objects": len(objs),
        "moving_objects": sum(1 for o in objs if any(o["velocity"]) or any(o["spin"])),
        "materials": kinds,
        "shapes": shapes,
        "lights": sorted({lt["type"] for lt in lights}),
        "portals": len(desc["lights"]) - len(lights),
        "small_bright_lights": sum(1 for lt in lights
                                   if lt["type"] in ("POINT", "SPOT") and lt["size"] <= 0.02),
        "moving_lights": sum(1 for lt in lights if any(lt["velocity"])),
        "switching_lights": sum(1 for lt in lights if lt["switch"]),
        "fading_lights": sum(1 for lt in lights if lt.get("fade")),
        "animated_emission": sum(1 for o in objs if o["material"].get("emission_keys")),
        "lighting_event": desc.get("lighting_event"),
        "world": desc["world"]["type"],
        "camera_motion": camera["motion"],
        "camera_speed_px": cam.speed_px(camera),
        "depth_of_field": camera["dof"] is not None,
        "motion_blur": desc["motion_blur"] is not None,
        "hard_surfaces": desc.get("hard_surfaces", 0),
    }


def describe(family, seed, frames=8):
    """The scene description of (``family``, ``seed``) animated over ``frames`` frames."""
    if family not in FAMILIES:
        raise ValueError("unknown family %r (known: %s)" % (family, ", ".join(FAMILIES)))
    if frames < 1:
        raise ValueError("frames must be >= 1")
    rng = random.Random("afn-scene:%s:%d" % (family, seed))
    layout = FAMILIES[family](rng, frames)
    effects = layout["effects"]
    objects = layout["objects"]
    camera = cam.camera(rng, layout["rig"], frames, p_dof=effects["dof"],
                        blocked=lambda p: any(inside(p, o) for o in objects))
    L.animate(rng, layout["lights"], frames, p_move=effects["move_light"],
              p_switch=effects["switch_light"])
    blur = {"shutter": round(rng.uniform(0.3, 1.0), 3)} if s.chance(rng, effects["blur"]) else None
    desc = {
        "format": FORMAT, "family": family, "seed": seed, "frames": frames,
        "world": layout["world"], "lights": layout["lights"], "objects": layout["objects"],
        "camera": camera, "motion_blur": blur,
        # Film exposure is set so the log-average luminance of frame 0 is this key (auto exposure).
        "exposure": {"key": round(s.log_uniform(rng, 0.08, 0.3), 4)},
        "render": dict(RENDER),
    }
    # Drawn last, so the layout, camera and exposure above do not depend on it.
    desc["lighting_event"] = lighting_change.add_event(rng, desc["lights"], desc["objects"],
                                                       camera, frames)
    # Drawn after the event: more metal, glass, depth of field and motion blur (surfaces.py).
    desc["hard_surfaces"] = surfaces.add_hard_surfaces(rng, desc)
    desc["summary"] = summary(desc)
    return desc


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    desc = describe(argv[0], int(argv[1]), int(argv[2]) if len(argv) > 2 else 8)
    json.dump(desc, sys.stdout, indent=1)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
