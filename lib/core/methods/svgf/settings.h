// SPDX-License-Identifier: Apache-2.0
// SVGF settings (Schied et al. 2017): paper values as defaults, Falcor's noted in the help texts.
// Ranges, labels and help are in settingsBinding() (atrous.cpp), one line per member.
#pragma once

#include "stages/highlight_bypass.h"

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
    /// Spread sparse samples in the 7x7 estimate (kernels.h sparseShare; not in the paper);
    /// auto: below kSpreadSpp samples per pixel, or when the count is unknown.
    enum class Spread { Auto, Off, On };
    Spread spread = Spread::Auto;
    int spp = 0; ///< the shared "spp" parameter (0: unknown)
    bool taa = false; ///< temporal anti-aliasing of the output (paper, Fig. 2; stages/taa.h);
                      ///< off by default while it disables work skipping (work_skip.cpp)
    float taaAlpha = 0.2f; ///< TAA weight of the current frame (stages/taa.h kTaaAlpha)
    /// Factor of the highlight bypass's limit over the frame's bright level, 0 = off
    /// (stages/highlight_bypass.h; not in the paper): the integrated colour is filtered clamped,
    /// the excess added back to the output and the history at its own pixel.
    float highlights = kHighlightFactor;
};

/// spread=auto spreads sparse samples below this many samples per pixel: from 16 spp on the
/// luminance differences of a neighbourhood are mostly the image's, and dropping their
/// edge-stopping cost 0.05-1 dB on the afn-v4 held-out sequences (docs/afn-evaluation.md).
constexpr int kSpreadSpp = 4;

/// Whether the 7x7 estimate spreads sparse samples under `s`.
inline bool spreadsSparseSamples(const Settings& s)
{
    return s.spread == Settings::Spread::On
        || (s.spread == Settings::Spread::Auto && s.spp < kSpreadSpp);
}

/// The descriptors of Settings (the method's own parameters).
const ParamBinding<Settings>& settingsBinding();

} // namespace afn::svgf
