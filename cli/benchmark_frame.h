// SPDX-License-Identifier: Apache-2.0
// Generated input frames for the synthetic benchmarks (--benchmark:size=..., :sky=...): plain
// fills plus hashed per-pixel noise, no rendering. Written by hand here; they carry no product
// pixel math.
#pragma once

#include "frame_loader.h"

namespace afntool {

/// Depth the generated sky carries: Blender Cycles' Depth.Z background value.
constexpr float kGeneratedSkyDepth = 1e10f;

/// Fill `f` with generated frame `frame` of w x h: a 1-spp-like noisy beauty over a lit plane
/// facing the camera (constant albedo, normal, depth 5; static camera, zero motion). With `sky`
/// in (0, 1], the top round(sky * h) rows are sky instead: depth kGeneratedSkyDepth, a smooth
/// blue gradient with faint noise. The roles are made on the first call (keep `sky` per `f`).
void makeFrame(LoadedFrame& f, int w, int h, int frame, double sky = 0.0);

/// The number of sky rows makeFrame gives a frame of height h.
int skyRows(int h, double sky);

/// The expected value of a covered pixel's beauty (every channel): the noiseless image the
/// covered rows estimate, E[v] for v = 0.3 u (u < 0.9), 4 u (u >= 0.9), u uniform in [0, 1):
/// 0.3 * 0.81 / 2 + 4 * 0.19 / 2 = 0.5015.
constexpr float kCoveredExpectation = 0.5015f;

} // namespace afntool
