# SPDX-License-Identifier: Apache-2.0
"""Blender side of test_generator_blender.py: build descriptions and render each one tiny frame.

Usage: blender -b --factory-startup --python blender_build_families.py -- LIST.json OUT_DIR
LIST.json holds descriptions; renders frame 0 of each at 16x9 px, 1 spp, to OUT_DIR/<family>.exr and
prints "built <family> <objects> <lights>" per description.
"""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scenes"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "examples", "blender"))
import afn_render  # noqa: E402
from generator import blender_build  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
with open(args[0]) as fh:
    descriptions = json.load(fh)
for desc in descriptions:
    scene = blender_build.build(desc)
    afn_render.setup(scene, "noisy", 16, 9, 1, 1)
    scene.render.threads_mode, scene.render.threads = "FIXED", 2
    afn_render.render_frame(scene, 0, os.path.join(args[1], desc["family"] + ".exr"))
    meshes = sum(1 for o in scene.objects if o.type in ("MESH", "CURVE", "FONT"))
    lights = sum(1 for o in scene.objects if o.type == "LIGHT")
    print("built %s %d %d" % (desc["family"], meshes, lights), flush=True)
