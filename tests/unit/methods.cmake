# SPDX-License-Identifier: Apache-2.0
# Demodulation, reprojection, temporal accumulation, SVGF and BMFR (lib/core/stages, lib/core/methods): internals
# and the filters through createFilter; test_methods_blender reads examples/sequence with OIIO.
afn_add_gtest(test_methods SOURCES unit/test_methods_reproject.cpp unit/test_methods_ta.cpp
  unit/test_methods_filters.cpp unit/test_methods_blender.cpp LIBS afn_core PkgConfig::OIIO)
