# SPDX-License-Identifier: Apache-2.0
"""Cycles render settings and the AOV pass set afn reads, shared by the example and training scenes.

Runs inside Blender 3.4 (``bpy``). Two output kinds:

* ``noisy``: ``samples`` per pixel (1 for afn inputs), every pass afn maps (Combined, Denoising
  Albedo/Normal/Depth, Normal, Position, Depth, Vector), OPEN_EXR_MULTILAYER, ZIP, half colour
  (Blender keeps Depth and Vector float).
* ``reference``: same scene and frame, only Combined, float32, many samples, a different noise seed so
  that reference noise is uncorrelated with the noisy input.

Choices (see docs/dataset.md): motion blur is off (otherwise Cycles writes an all-zero Vector pass);
adaptive sampling and the built-in denoiser are off (Debian's Blender has no OIDN anyway); the film
is opaque; the noise seed changes every frame (``seed + frame``).
"""

import os
import time

import bpy

VIEW_LAYER_NAME = "ViewLayer"

# Offset added to the seed of reference renders so their noise never matches the noisy frame's.
REFERENCE_SEED_OFFSET = 7919


def configure_cycles(scene, width, height, samples, seed):
    """Set Cycles CPU, resolution (pixels), sample count and noise seed; no denoiser, no blur."""
    scene.render.engine = "CYCLES"
    cyc = scene.cycles
    cyc.device = "CPU"
    cyc.samples = int(samples)
    cyc.use_adaptive_sampling = False
    cyc.use_denoising = False
    cyc.seed = int(seed)
    cyc.use_animated_seed = True  # noise seed = seed + frame: decorrelated from frame to frame
    scene.render.use_motion_blur = False
    scene.render.film_transparent = False
    scene.render.resolution_x = int(width)
    scene.render.resolution_y = int(height)
    scene.render.resolution_percentage = 100
    scene.render.use_persistent_data = True
    scene.view_settings.view_transform = "Standard"  # EXR is scene-linear regardless; for previews


LIGHT_PASSES = ("diffuse_direct", "diffuse_indirect", "diffuse_color", "glossy_direct",
                "glossy_indirect", "glossy_color", "transmission_direct", "transmission_indirect",
                "transmission_color", "emit", "environment")


def configure_passes(scene, all_passes, light_passes=False):
    """Enable every pass afn maps (``all_passes``) or Combined only (references); with
    ``light_passes`` also the light-path passes a compositor rebuilds Combined from (DiffDir,
    DiffInd, DiffCol, Gloss*, Trans*, Emit, Env)."""
    layer = scene.view_layers[0]
    for name in LIGHT_PASSES:
        setattr(layer, "use_pass_" + name, bool(light_passes))
    layer.name = VIEW_LAYER_NAME
    layer.use_pass_combined = True
    layer.use_pass_normal = all_passes
    layer.use_pass_position = all_passes
    layer.use_pass_z = all_passes
    layer.use_pass_vector = all_passes
    layer.cycles.denoising_store_passes = all_passes
    scene.use_nodes = False  # no compositor layer in the file


def configure_output(scene, half):
    """Multilayer EXR, ZIP; half colour channels when ``half`` (Depth/Vector stay float)."""
    img = scene.render.image_settings
    img.file_format = "OPEN_EXR_MULTILAYER"
    img.color_depth = "16" if half else "32"
    img.exr_codec = "ZIP"
    img.color_mode = "RGBA"
    scene.render.use_file_extension = True


def setup(scene, kind, width, height, samples, seed, ref_seed_offset=REFERENCE_SEED_OFFSET,
          light_passes=False):
    """Configure ``scene`` for one output kind, ``"noisy"`` or ``"reference"``.

    References use noise seed ``seed + ref_seed_offset``.
    """
    if kind not in ("noisy", "reference"):
        raise ValueError("unknown render kind: %r" % kind)
    noisy = kind == "noisy"
    configure_cycles(scene, width, height, samples, seed if noisy else seed + ref_seed_offset)
    configure_passes(scene, all_passes=noisy, light_passes=light_passes)
    configure_output(scene, half=noisy)


def render_frame(scene, frame, path):
    """Render ``frame`` to ``path`` (``.exr`` appended by Blender if missing); return seconds."""
    scene.frame_set(frame)
    base = path[:-4] if path.endswith(".exr") else path
    scene.render.filepath = base
    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    seconds = time.time() - t0
    if not os.path.exists(base + ".exr"):
        raise RuntimeError("Blender did not write %s.exr" % base)
    return seconds


def set_linear(obj):
    """Make every keyframe of ``obj`` linear (constant velocity, so Vector XY == ZW)."""
    ad = obj.animation_data
    if ad is None or ad.action is None:
        return
    for fc in ad.action.fcurves:
        for kp in fc.keyframe_points:
            kp.interpolation = "LINEAR"
        fc.extrapolation = "LINEAR"
