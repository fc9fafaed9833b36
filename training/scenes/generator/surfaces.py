# SPDX-License-Identifier: Apache-2.0
"""Hard surfaces for the denoiser: more metal, glass and glossy objects, depth of field, motion blur.

A path tracer's albedo and normal passes are exact on diffuse surfaces and noisy on the surfaces a
denoiser finds hardest: behind glass the albedo is the albedo of whatever one refracted sample
hit, on a rough metal the first-bounce normal varies inside the pixel, in depth of field and
motion blur both are averages of several surfaces. A network that learned to trust its albedo and
normal everywhere leaves dark specks on glass and blotches on gold there (docs/afn-evaluation.md,
"Auxiliary buffers that do not hold"). So, drawn after everything else (the layout, camera,
exposure and lighting event of a description do not depend on it):

* each object of prop size (under :data:`PROP_SIZE` m, not flat, not emissive) becomes a hard
  surface with chance :data:`P_HARD`, drawn from :data:`HARD_KINDS` (polished and rough metals,
  clear and frosted glass, clear-coat, glossy plastic); a scene with props has at least one;
* a scene without depth of field gets it with chance :data:`P_EXTRA_DOF`, and one without motion
  blur gets it with chance :data:`P_EXTRA_BLUR`; the families' own chances come first.
"""

from . import materials as mats
from . import sampling as s

P_HARD = 0.3
PROP_SIZE = 2.5
HARD_KINDS = {"metal_mirror": 1.5, "glass": 1.5, "metal_rough": 1.2, "coated": 1.0,
              "frosted_glass": 0.7, "plastic": 0.8}
P_EXTRA_DOF = 0.2
P_EXTRA_BLUR = 0.2
FLAT_SHAPES = ("plane", "grass", "text", "wire_grid")


def _is_prop(o):
    m = o["material"]
    return (o["shape"] not in FLAT_SHAPES and max(o["dims"]) < PROP_SIZE
            and m["kind"] != "emissive" and not m.get("emission_keys"))


def add_hard_surfaces(rng, desc):
    """Re-surface props, add depth of field and motion blur to ``desc`` in place.

    Returns the number of objects re-surfaced (recorded as ``hard_surfaces``).
    """
    props = [o for o in desc["objects"] if _is_prop(o)]
    chosen = [o for o in props if s.chance(rng, P_HARD)]
    if props and not chosen:
        chosen = [max(props, key=lambda o: max(o["dims"]))]
    for o in chosen:
        o["material"] = mats.material(rng, weights=HARD_KINDS)
    camera = desc["camera"]
    if camera["dof"] is None and s.chance(rng, P_EXTRA_DOF):
        mid = camera["keys"][len(camera["keys"]) // 2]
        focus = s.length(s.sub(mid["target"], mid["location"])) * rng.uniform(0.6, 1.2)
        camera["dof"] = {"fstop": round(s.log_uniform(rng, 0.7, 4.0), 3),
                         "focus_distance": round(focus, 4)}
    if desc["motion_blur"] is None and s.chance(rng, P_EXTRA_BLUR):
        desc["motion_blur"] = {"shutter": round(rng.uniform(0.3, 1.0), 3)}
    return len(chosen)
