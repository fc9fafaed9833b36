# SPDX-License-Identifier: Apache-2.0
"""Randomized scene generator for afn's training and evaluation data (docs/dataset.md).

Two halves that meet in a JSON scene description:

* pure Python (no ``bpy``; runs under /usr/bin/python3 and in tests): :mod:`.describe` turns a
  (family, seed) pair into a description, drawing layouts from :mod:`.families`, materials from
  :mod:`.materials`, lights from :mod:`.lighting` and camera paths from :mod:`.camera`;
  :mod:`.split` says which pairs train and which are held out for evaluation;
* Blender (``bpy``): :mod:`.blender_build` builds a description into a scene with the meshes of
  :mod:`.blender_meshes` and the materials of :mod:`.blender_materials`; :mod:`.blender_runner`
  renders it.
"""
