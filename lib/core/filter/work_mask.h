// SPDX-License-Identifier: Apache-2.0
// Work skipping: which pixels of a frame need denoising. The Filter base fills
// Frame::work once per frame from the caller's bindings, before the stages run:
//   - background / sky: the depth input is non-finite or >= denoisingRange (NRD's
//     denoisingRange); without depth, a position input with a non-finite component or a length
//     >= denoisingRange. Renderers' "infinite" depth: Blender Cycles' Depth.Z writes 1e10 for
//     the background, Arnold, Karma and others inf or FLT_MAX; the default range 1e9 catches all
//     of them and no scene in scene units reaches it. Depth is read from the binding as given
//     (before the gather replaces inf by 0), so an inf depth counts as background.
//   - alpha == 0 where an alpha input is bound (nothing covers the pixel);
//   - a user mask (AFN_IMAGE_MASK, 1 channel; a FLOAT2-4 binding is read in its first channel):
//     a pixel needs denoising only where the mask is > 0 (NaN counts as 0).
// A pixel needs denoising when none of these rules says otherwise. When every pixel needs it the
// mask stays empty (Frame::hasWorkMask() false) and methods run exactly as without skipping;
// `skip=off` never builds it. What a method does with masked-out pixels (its "cheap path") and
// how it keeps the others bit-identical is documented at the method (docs/work-skipping.md).
#pragma once

#include "base/params.h"
#include "filter/frame.h"

#include <map>
#include <string>
#include <vector>

namespace afn {

struct ImageBinding;

/// Parameters of work skipping (appended to every filter type's table).
struct WorkSettings {
    bool skip = true; ///< let pixels that need no denoising take the method's cheap path
    /// [0, 3.4e38] scene units; depth (or position length) at or beyond it is background
    /// (NRD denoisingRange; Blender Cycles' background depth is 1e10)
    float denoisingRange = 1e9f;
};

/// The descriptors of WorkSettings ("skip", "denoisingRange").
const ParamBinding<WorkSettings>& workBinding();
/// The same descriptors for one method: `skipHelp` (FilterType::skipHelp: what skipping does in
/// that method) is appended to the help of "skip"; empty says skipping is not implemented there.
std::vector<ParamDesc> workDescriptors(const std::string& skipHelp);

/// Fill `frame.work` (frame size, gathered) from the raw depth / position bindings, the gathered
/// alpha and the mask binding; leaves it empty when skipping is off or every pixel needs work.
/// Returns the share in [0, 1] of pixels that need no denoising.
double buildWorkMask(
    const std::map<std::string, ImageBinding>& images, const WorkSettings& s, Frame& frame);

} // namespace afn
