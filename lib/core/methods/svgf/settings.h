// SPDX-License-Identifier: Apache-2.0
// SVGF settings (Schied et al. 2017): paper values as defaults, Falcor's noted in the help texts.
// Ranges, labels and help are in settingsBinding() (atrous.cpp), one line per member.
#pragma once

#include "base/params.h"

namespace afn::svgf {

struct Settings {
    int iterations = 5; ///< à-trous iterations
    int feedbackTap = 0; ///< iteration whose output becomes the colour history
    float sigmaL = 4.0f; ///< luminance edge-stopping, in local standard deviations
    float sigmaN = 128.0f; ///< normal exponent
    float sigmaZ = 1.0f; ///< depth edge-stopping, relative to the depth gradient
    float alpha = 0.2f; ///< minimum colour blend factor
    float momentsAlpha = 0.2f; ///< minimum moments blend factor
    int varianceHistory = 4; ///< history length below which variance is estimated over 7x7
};

/// The descriptors of Settings (the method's own parameters).
const ParamBinding<Settings>& settingsBinding();

} // namespace afn::svgf
