// SPDX-License-Identifier: Apache-2.0
// One SVGF à-trous iteration on colour + variance (see methods/svgf/denoiser.h; the per-row
// kernels are in atrous_kernel.cpp and atrous_avx512.cpp, chosen here by cpu::activeIsa()) and
// the method's parameter table.
#include "base/parallel.h"
#include "cpu/isa.h"
#include "methods/svgf/denoiser.h"
#include "methods/svgf/kernels.h"

#include <algorithm>

namespace afn::svgf {

void atrousRows(const AtrousArgs& a, int y0, int y1)
{
    if (cpu::activeIsa() == cpu::Isa::Avx512)
        atrousRowsAvx512(a, y0, y1);
    else
        atrousRowsPortable(a, y0, y1);
}

void Denoiser::atrous(const Planes& in, Planes& out, int step, const WorkRegion* region)
{
    const int w = in.width(), h = in.height();
    if (out.width() != w || out.height() != h || out.count() < kColorPlanes)
        out.resize(w, h, kColorPlanes); // a larger buffer (the integration planes) serves as is
    AtrousArgs a;
    a.in = &in;
    a.sigmaL = m_settings.sigmaL;
    a.guide = &m_guide;
    a.out = &out;
    a.step = step;
    a.region = region;
    m_rowOrder.clear();
    for (int r = 0; r < step; ++r)
        for (int y = r; y < h; y += step)
            m_rowOrder.push_back(y);
    a.rowOrder = m_rowOrder.data();
    // Column tiles (kernels.h AtrousArgs::x0): one pass over all rows per tile.
    for (int x0 = 0; x0 < w; x0 += kAtrousTile) {
        a.x0 = x0;
        a.x1 = std::min(w, x0 + kAtrousTile);
        parallelRows(h, [&](int y0, int y1) { atrousRows(a, y0, y1); });
    }
}

const ParamBinding<Settings>& settingsBinding()
{
    using S = Settings;
    static const ParamBinding<S> binding
        = ParamBinding<S>()
              .add(&S::iterations, "iterations", 0, 10, "À-trous iterations",
                  "number of 5x5 à-trous passes with step 2^i (paper 5, Falcor 4)")
              .add(&S::feedbackTap, "feedbackTap", -1, 9, "Feedback iteration",
                  "iteration whose output becomes the colour history (0 = first, as the paper; "
                  "-1 or >= iterations = unfiltered integrated colour; Falcor 1)")
              .add(&S::sigmaL, "sigmaL", 0.0, 1000.0, "Luminance sigma",
                  "luminance edge-stopping, in standard deviations of the local luminance "
                  "(paper 4, Falcor 10)")
              .add(&S::sigmaN, "sigmaN", 0.0, 1024.0, "Normal exponent",
                  "exponent of max(0, n.n') (paper and Falcor 128)")
              .add(&S::sigmaZ, "sigmaZ", 0.0, 1000.0, "Depth sigma",
                  "depth edge-stopping relative to the depth gradient (paper 1)")
              .add(&S::alpha, "alpha", 0.0, 1.0, "Colour blend factor",
                  "minimum weight of the current frame in the colour history (paper 0.2, "
                  "Falcor 0.05)")
              .add(&S::momentsAlpha, "momentsAlpha", 0.0, 1.0, "Moments blend factor",
                  "minimum weight of the current frame in the moments history (paper 0.2)")
              .add(&S::varianceHistory, "varianceHistory", 1, 255, "Spatial variance below",
                  "history length (frames) below which variance is estimated over 7x7 (paper 4)")
              .add(&S::spread, "spread",
                  { { "auto", S::Spread::Auto }, { "off", S::Spread::Off },
                      { "on", S::Spread::On } },
                  "Spread sparse samples",
                  "where the history is short (first frames, cuts, disocclusions), drop the "
                  "luminance edge-stopping of the 7x7 estimate in neighbourhoods of a few bright "
                  "samples among dark ones (coefficient of variation 1 -> 3), so that their "
                  "light spreads instead of staying in single bright pixels over a dark frame; "
                  "not in the paper; auto: below 4 spp or when the sample count is unknown")
              .add(&S::highlights, "highlights", 0.0, 1e6, "Highlight bypass",
                  "values of the temporally integrated colour above this factor times the "
                  "frame's bright level (the power of two above its 99th percentile) skip the "
                  "a-trous filter: it reads them clamped and the excess is added back at its own "
                  "pixel, in the output and the history, so a small light or glint stays a "
                  "point instead of a blotch; not in the paper; 0 = off")
              .add(&S::taa, "taa", "TAA",
                  "temporal anti-aliasing of the remodulated output, the paper's last step "
                  "(history clamped to the current frame's 3x3 neighbourhood in YCoCg): smooths "
                  "silhouettes and flicker at 1 spp; blurs sharper 16-spp results; with it no "
                  "pixel is skipped")
              .add(&S::taaAlpha, "taaAlpha", 0.0, 1.0, "TAA blend factor",
                  "weight of the current frame in the TAA blend (0.2, as BMFR's)");
    return binding;
}

} // namespace afn::svgf
