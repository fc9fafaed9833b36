// SPDX-License-Identifier: Apache-2.0
// The afn method's own parameters (besides the shared aux/spp, quality and skip ones).
//
// taa: temporal anti-aliasing of the remodulated output (stages/taa.h, the last step of SVGF and
// BMFR; not in the AFN paper): each frame's output is blended with the previous output,
// reprojected and clamped in YCoCg to the current frame's 3x3 neighbourhood.
//   auto (default)  on when the model that runs the frame was trained below 16 spp (the 1-spp
//                   models), off for the 16- and 64-spp models
//   off, on         as named
// Why auto: on the held-out set (docs/afn-evaluation.md, seventeenth session) TAA with a blend
// factor of 0.5 raised afn's 1-spp mean PSNR by 0.16 dB and SSIM by 0.014 and cut the temporal
// error by 8 %, but lost PSNR at 16 spp on 4 of 5 sequences (up to 1.3 dB): a sharp 16-spp
// result has little flicker left to remove and the clamp box blurs it. The factor 0.5 was chosen
// there between 0.2 (BMFR's, -0.8 dB on examples/sequence) and 0.5.
// With TAA on, every pixel is denoised (no work skipping: the TAA reads its neighbourhood and the
// next frame reads its history).
#pragma once

#include "base/params.h"

namespace afn::afnet {

struct Settings {
    enum class Taa { Auto, Off, On };
    Taa taa = Taa::Auto; ///< temporal anti-aliasing of the output (stages/taa.h)
    float taaAlpha = 0.5f; ///< TAA weight of the current frame
};

/// Models trained at this many samples per pixel or more run without TAA under taa=auto.
constexpr int kTaaAutoMaxSppExclusive = 16;

/// The descriptors of Settings (settings.cpp).
const ParamBinding<Settings>& settingsBinding();

} // namespace afn::afnet
