# SPDX-License-Identifier: Apache-2.0
"""Build Blender materials from the generator's JSON material descriptions (``materials.py``).

Runs inside Blender 3.4. Textures use Object coordinates; ``blender_meshes.py`` applies object
scale, so a texture ``scale`` is a frequency per metre and stays put on moving objects.
"""

import bpy

_cache = {}


def _rgba(c):
    return (float(c[0]), float(c[1]), float(c[2]), 1.0)


def _texture(nodes, links, tex, base):
    """Procedural texture node mixing ``base`` and ``tex['colour2']``; returns its colour output."""
    coord = nodes.new("ShaderNodeTexCoord")
    kind = tex["type"]
    if kind in ("checker", "brick"):
        node = nodes.new("ShaderNodeTexChecker" if kind == "checker" else "ShaderNodeTexBrick")
        node.inputs["Color1"].default_value = _rgba(base)
        node.inputs["Color2"].default_value = _rgba(tex["colour2"])
        if kind == "brick":
            node.inputs["Mortar"].default_value = (0.05, 0.05, 0.05, 1.0)
        out = node.outputs["Color"]
    else:
        node = nodes.new({"noise": "ShaderNodeTexNoise", "voronoi": "ShaderNodeTexVoronoi",
                          "wave": "ShaderNodeTexWave", "magic": "ShaderNodeTexMagic"}[kind])
        if kind == "noise":
            node.inputs["Detail"].default_value = 6.0
        mix = nodes.new("ShaderNodeMixRGB")
        mix.inputs["Color1"].default_value = _rgba(base)
        mix.inputs["Color2"].default_value = _rgba(tex["colour2"])
        fac = node.outputs["Fac"] if "Fac" in node.outputs else node.outputs["Distance"]
        links.new(fac, mix.inputs["Fac"])
        out = mix.outputs["Color"]
    node.inputs["Scale"].default_value = float(tex["scale"])
    links.new(coord.outputs["Object"], node.inputs["Vector"])
    return out


def _key_emission(mat, socket, keys, interp):
    """Key the emission strength at ``keys`` ``[[frame, strength], ...]``, held after the last."""
    for frame, strength in keys:
        socket.default_value = strength
        socket.keyframe_insert("default_value", frame=frame)
    for fc in mat.node_tree.animation_data.action.fcurves:
        fc.extrapolation = "CONSTANT"
        for kp in fc.keyframe_points:
            kp.interpolation = interp


def material(desc, name="m"):
    """A Principled-BSDF material for ``desc``; identical descriptions share one material."""
    key = repr(sorted(desc.items()))
    if key in _cache and _cache[key].name in bpy.data.materials:
        return _cache[key]
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    inp = bsdf.inputs
    inp["Base Color"].default_value = _rgba(desc["base"])
    inp["Roughness"].default_value = desc["roughness"]
    inp["Metallic"].default_value = desc["metallic"]
    inp["Specular"].default_value = desc["specular"]
    inp["Transmission"].default_value = desc["transmission"]
    inp["IOR"].default_value = desc["ior"]
    inp["Clearcoat"].default_value = desc["clearcoat"]
    inp["Clearcoat Roughness"].default_value = desc["clearcoat_roughness"]
    if desc["emission_strength"] > 0 or desc.get("emission_keys"):
        inp["Emission"].default_value = _rgba(desc["emission"])
        inp["Emission Strength"].default_value = desc["emission_strength"]
    if desc.get("emission_keys"):
        _key_emission(mat, inp["Emission Strength"], desc["emission_keys"], desc["emission_interp"])
    if desc["texture"]:
        links.new(_texture(nodes, links, desc["texture"], desc["base"]), inp["Base Color"])
    if desc["translucency"] > 0:
        out = nodes["Material Output"]
        trans = nodes.new("ShaderNodeBsdfTranslucent")
        trans.inputs["Color"].default_value = _rgba(desc["base"])
        mix = nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = desc["translucency"]
        links.new(bsdf.outputs["BSDF"], mix.inputs[1])
        links.new(trans.outputs["BSDF"], mix.inputs[2])
        links.new(mix.outputs["Shader"], out.inputs["Surface"])
    _cache[key] = mat
    return mat


def reset():
    """Forget cached materials (call after clearing the scene)."""
    _cache.clear()
