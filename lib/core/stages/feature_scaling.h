// SPDX-License-Identifier: Apache-2.0
// Auxiliary-feature scaling of the learned methods' inputs (afn, and through nn/baseline_input.h
// the baselines wskpn and nbgd; training/afn/color.py has the same rules):
//   normal01 = clip(n * 0.5 + 0.5, 0, 1)   (zero normal -> 0.5)
//   depth01  = (z - min) / (max - min) over the valid depths of the frame (WSKPN); a depth is
//              valid when finite and |z| < kDepthSky (Blender writes 1e10 for the sky);
//              invalid -> 1 (far); a constant depth -> 0.
#pragma once

#include "base/image.h"

namespace afn {

/// Depths at or beyond this are "no surface".
constexpr float kDepthSky = 1e9f;

/// Shading normal (3 ch) to [0, 1]; an empty input gives 0.5 everywhere of size w x h.
void normalToUnitRange(const Image& normal, int w, int h, Image& out);
/// Per-frame min-max depth (1 ch) to [0, 1]; an empty input gives 0 everywhere of size w x h.
void depthToUnitRange(const Image& depth, int w, int h, Image& out);

} // namespace afn
