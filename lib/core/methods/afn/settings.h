// SPDX-License-Identifier: Apache-2.0
// AFN settings. The sample count of the input picks the model trained for it (the paper's AFN for
// low counts, AFN large for high ones, once both ship); the host reads it from the file (afntool:
// Blender's cycles.<layer>.samples header) unless the user sets it. Ranges, labels and help are in
// settingsBinding() (afn_method.cpp).
#pragma once

#include "base/params.h"

namespace afn::afnet {

struct Settings {
    int spp = 0; ///< samples per pixel of the colour input; 0 = unknown (treated as low)
};

/// The descriptors of Settings (the method's own parameters).
const ParamBinding<Settings>& settingsBinding();

} // namespace afn::afnet
