// SPDX-License-Identifier: Apache-2.0
// One frame of canonical inputs, as every denoising method sees it. The Filter base converts the
// caller's buffers into this form once per frame ("convert once"):
//   color    3 ch  linear RGB radiance; NaN/Inf replaced by 0 and negatives clamped to 0 (counted)
//   albedo   3 ch  [0, 1]; absent -> empty (methods then treat albedo as 1)
//   normal   3 ch  unit shading normal; space given by `normalSpace` (camera = +Z into the scene)
//   depth    1 ch  linear distance; `depthKind` says planar (camera z) or radial (ray length)
//   position 3 ch  world-space position, scene units
//   motion   2 ch  pixels, y down (row order), offset from this pixel to where the surface was in
//                  the previous frame: prev = (x + mx, y + my)
//   alpha    1 ch  coverage, passed through to the output
// Non-finite values in geometry buffers are replaced by 0 and counted; a pixel with a zero normal
// never accepts history. For methods that demodulate (StageNeeds::demodulate), the demodulation
// stage overwrites `color` in place with the irradiance (stages/demodulate.h): the frame a method
// sees then holds irradiance there (Filter::irradiance()), not radiance.
#pragma once

#include "base/image.h"

#include <array>
#include <cstdint>

namespace afn {

enum class NormalSpace { World, Camera };
enum class DepthKind { Planar, Radial };

/// Per-frame camera for reprojection from world positions (BMFR dataset convention).
struct Camera {
    bool valid = false;
    std::array<float, 16> viewProjection {}; ///< row-major, row-vector convention: clip = [p,1]·M
    std::array<float, 2> pixelOffset { 0.5f, 0.5f }; ///< sub-pixel sample offset of this frame
};

/// Counts of sanitised input values during one gather.
struct InputStats {
    std::int64_t nonFinite = 0; ///< NaN/Inf values replaced by 0 (all inputs)
    std::int64_t negative = 0; ///< negative colour values clamped to 0
};

struct Frame {
    int width = 0;
    int height = 0;
    Image color;
    Image albedo;
    Image normal;
    Image depth;
    Image position;
    Image motion;
    Image alpha;
    Image work; ///< 1 ch: 1 where the pixel needs denoising, 0 where it may take the cheap path
                ///< (work skipping); empty = every pixel needs it
    NormalSpace normalSpace = NormalSpace::World;
    DepthKind depthKind = DepthKind::Planar;
    bool colorDemodulated = false; ///< colour is already divided by albedo (BMFR dataset)
    Camera camera; ///< this frame's camera (valid only when given)
    Camera prevCamera; ///< the previous executed frame's camera (invalid after reset)
    int frameIndex = 0; ///< frames since the last reset (0 = first)

    bool hasAlbedo() const { return !albedo.empty(); }
    bool hasNormal() const { return !normal.empty(); }
    bool hasDepth() const { return !depth.empty(); }
    bool hasPosition() const { return !position.empty(); }
    bool hasMotion() const { return !motion.empty(); }
    bool hasWorkMask() const { return !work.empty(); }
};

} // namespace afn
