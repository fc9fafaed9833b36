// SPDX-License-Identifier: Apache-2.0
// Conventions of the bound inputs: parameters every filter has (AFN_CONVENTION_* in afn.h). The
// gather (filter/gather.cpp) converts inputs in these conventions into the canonical Frame.
#pragma once

#include "base/params.h"
#include "filter/frame.h"

namespace afn {

struct InputConventions {
    /// Space of the normal input; CameraTowardViewer is a camera space with +Z toward the viewer.
    enum class Normals { World, Camera, CameraTowardViewer };
    /// Where the motion vectors point.
    enum class MotionDirection { ToPrevious, ToNext };
    /// Units of the motion vectors.
    enum class MotionUnits { Pixels, Ndc, Uv };

    Normals normalSpace = Normals::World;
    DepthKind depthKind = DepthKind::Planar;
    MotionDirection motionDirection = MotionDirection::ToPrevious;
    bool motionYUp = false;
    MotionUnits motionUnits = MotionUnits::Pixels;
    float motionScale = 1.0f;
    bool colorDemodulated = false;
};

/// The descriptors of InputConventions (appended to every filter type's table).
const ParamBinding<InputConventions>& conventionsBinding();

} // namespace afn
