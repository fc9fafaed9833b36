# SPDX-License-Identifier: Apache-2.0
"""Material library of the scene generator: draws JSON material descriptions (no ``bpy``).

A material is a dict with ``kind`` (one of :data:`KINDS`) and Principled-BSDF parameters:
``base`` (linear RGB), ``roughness``, ``metallic``, ``transmission``, ``ior``, ``clearcoat``,
``clearcoat_roughness``, ``specular``, ``emission`` (RGB) and ``emission_strength``,
``translucency`` (share of a Translucent BSDF mixed in), and ``texture`` (``None`` or a procedural
texture that drives the base colour: ``type`` checker/brick/noise/voronoi/wave/magic, ``scale``,
``colour2``). ``blender_materials.py`` turns it into nodes.
"""

from . import sampling as s

# Material kinds and their default relative frequency.
KINDS = {
    "diffuse": 2.0,             # plain rough dielectric
    "textured": 3.0,            # procedural base colour, coarse to very fine
    "plastic": 1.5,             # glossy dielectric, roughness 0.05..0.3
    "metal_rough": 1.5,         # brushed / rough metal
    "metal_mirror": 1.0,        # polished metal, roughness < 0.05
    "glass": 1.0,               # clear refractive
    "frosted_glass": 0.7,       # rough refraction
    "translucent": 0.6,         # thin translucent (paper, leaves, lamp shades)
    "coated": 1.2,              # clearcoat over a diffuse or textured base (car paint, lacquer)
    "emissive": 0.4,            # glowing surface
}

# Reflectance (F0, linear) of common metals.
METALS = {
    "gold": (1.0, 0.77, 0.34), "copper": (0.95, 0.64, 0.54), "silver": (0.97, 0.96, 0.91),
    "aluminium": (0.91, 0.92, 0.92), "iron": (0.56, 0.57, 0.58), "brass": (0.91, 0.78, 0.42),
    "chrome": (0.55, 0.56, 0.55), "titanium": (0.54, 0.5, 0.45),
}

TEXTURES = {"checker": 1.0, "brick": 1.0, "noise": 1.5, "voronoi": 1.0, "wave": 1.0, "magic": 0.7}


def _base(kind):
    return {"kind": kind, "base": [0.5, 0.5, 0.5], "roughness": 0.5, "metallic": 0.0,
            "transmission": 0.0, "ior": 1.45, "clearcoat": 0.0, "clearcoat_roughness": 0.03,
            "specular": 0.5, "emission": [0.0, 0.0, 0.0], "emission_strength": 0.0,
            "translucency": 0.0, "texture": None}


def texture(rng, fine=False):
    """A procedural base-colour texture; ``fine`` favours high frequencies (sub-pixel detail)."""
    kind = s.pick(rng, TEXTURES)
    lo, hi = (20.0, 300.0) if fine else (1.5, 40.0)
    return {"type": kind, "scale": round(s.log_uniform(rng, lo, hi), 3),
            "colour2": s.colour(rng, val=(0.02, 0.8))}


def material(rng, kind=None, weights=None, fine_texture=0.3):
    """Draw a material of ``kind`` (or of a kind drawn from ``weights``, default :data:`KINDS`).

    ``fine_texture`` is the chance that a texture is drawn at high frequency.
    """
    kind = kind or s.pick(rng, weights or KINDS)
    m = _base(kind)
    if kind == "diffuse":
        m.update(base=s.colour(rng), roughness=round(rng.uniform(0.6, 1.0), 3))
    elif kind == "textured":
        m.update(base=s.colour(rng), roughness=round(rng.uniform(0.35, 0.95), 3),
                 texture=texture(rng, fine=s.chance(rng, fine_texture)))
    elif kind == "plastic":
        m.update(base=s.colour(rng, sat=(0.3, 1.0)), roughness=round(rng.uniform(0.05, 0.3), 3),
                 specular=round(rng.uniform(0.4, 0.8), 3))
    elif kind in ("metal_rough", "metal_mirror"):
        name = rng.choice(sorted(METALS))
        rough = rng.uniform(0.15, 0.5) if kind == "metal_rough" else rng.uniform(0.0, 0.05)
        m.update(base=list(METALS[name]), metallic=1.0, roughness=round(rough, 3), metal=name)
        if kind == "metal_rough" and s.chance(rng, 0.3):
            m["texture"] = texture(rng, fine=True)
            m["texture"]["colour2"] = [round(c * 0.6, 4) for c in METALS[name]]
    elif kind in ("glass", "frosted_glass"):
        tint = s.colour(rng, sat=(0.0, 0.35), val=(0.85, 1.0))
        rough = 0.0 if kind == "glass" else rng.uniform(0.08, 0.35)
        m.update(base=tint, transmission=1.0, roughness=round(rough, 3),
                 ior=round(rng.uniform(1.3, 1.65), 3), specular=0.5)
    elif kind == "translucent":
        m.update(base=s.colour(rng, val=(0.4, 0.95)), roughness=round(rng.uniform(0.4, 0.8), 3),
                 translucency=round(rng.uniform(0.3, 0.7), 3))
    elif kind == "coated":
        m.update(base=s.colour(rng, sat=(0.3, 1.0), val=(0.1, 0.8)),
                 roughness=round(rng.uniform(0.3, 0.8), 3), clearcoat=1.0,
                 clearcoat_roughness=round(rng.uniform(0.0, 0.08), 3))
        if s.chance(rng, 0.4):
            m["texture"] = texture(rng)
        if s.chance(rng, 0.3):
            m.update(metallic=1.0, roughness=round(rng.uniform(0.3, 0.6), 3))  # metallic paint
    elif kind == "emissive":
        col = s.colour(rng, sat=(0.0, 1.0), val=(0.7, 1.0))
        m.update(base=[0.05, 0.05, 0.05], emission=col,
                 emission_strength=round(s.log_uniform(rng, 2.0, 30.0), 3))
    else:
        raise ValueError("unknown material kind %r" % kind)
    return m


def emissive(rng, strength_range=(2.0, 30.0), colour=None):
    """An emissive material with strength drawn log-uniformly from ``strength_range``."""
    m = material(rng, "emissive")
    m["emission_strength"] = round(s.log_uniform(rng, *strength_range), 3)
    if colour is not None:
        m["emission"] = list(colour)
    return m


def ground(rng, fine=None):
    """A floor/ground material: textured diffuse most of the time, sometimes coated or glossy."""
    kind = s.pick(rng, {"textured": 5.0, "coated": 1.5, "plastic": 1.0, "diffuse": 1.0})
    m = material(rng, kind)
    if kind != "textured" and s.chance(rng, 0.5):
        m["texture"] = texture(rng, fine=bool(fine) if fine is not None else s.chance(rng, 0.4))
    m["base"] = [round(min(c, 0.6), 4) for c in m["base"]]  # keep floors from glowing white
    return m
