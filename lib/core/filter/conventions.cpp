// SPDX-License-Identifier: Apache-2.0
#include "filter/conventions.h"

namespace afn {

const ParamBinding<InputConventions>& conventionsBinding()
{
    using C = InputConventions;
    static const ParamBinding<C> binding
        = ParamBinding<C>()
              .add(&C::normalSpace, AFN_CONVENTION_NORMAL_SPACE,
                  { { "world", C::Normals::World }, { "camera", C::Normals::Camera },
                      { "camera-toward-viewer", C::Normals::CameraTowardViewer } },
                  "Normal space",
                  "space of the normal input: world, camera (+Z into the scene, Blender's "
                  "Denoising Normal) or camera-toward-viewer (+Z toward the viewer, V-Ray)")
              .add(&C::depthKind, AFN_CONVENTION_DEPTH_KIND,
                  { { "planar", DepthKind::Planar }, { "radial", DepthKind::Radial } },
                  "Depth kind", "planar camera-z depth or radial ray distance")
              .add(&C::motionDirection, AFN_CONVENTION_MOTION_DIRECTION,
                  { { "to-previous", C::MotionDirection::ToPrevious },
                      { "to-next", C::MotionDirection::ToNext } },
                  "Motion direction",
                  "motion vectors point to where the surface was (to-previous) or will be "
                  "(to-next; negated under a constant-velocity assumption)")
              .add(&C::motionYUp, AFN_CONVENTION_MOTION_Y_UP, "Motion y up",
                  "motion y grows upward (Blender's Vector pass); false = y grows with the row")
              .add(&C::motionUnits, AFN_CONVENTION_MOTION_UNITS,
                  { { "pixels", C::MotionUnits::Pixels }, { "ndc", C::MotionUnits::Ndc },
                      { "uv", C::MotionUnits::Uv } },
                  "Motion units",
                  "pixels of the input resolution, NDC ([-1,1] across the frame) or UV ([0,1])")
              .add(&C::motionScale, AFN_CONVENTION_MOTION_SCALE, 0.0, 1000.0, "Motion scale",
                  "factor applied to the motion vectors (a host's render scale)")
              .add(&C::colorDemodulated, AFN_CONVENTION_COLOR_DEMODULATED, "Colour demodulated",
                  "the colour input is already divided by albedo (BMFR dataset)");
    return binding;
}

} // namespace afn
