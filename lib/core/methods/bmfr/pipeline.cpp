// SPDX-License-Identifier: Apache-2.0
// BMFR per-frame pipeline: TA, regression, second accumulation, remodulation, TAA (see
// methods/bmfr/denoiser.h).
#include "methods/bmfr/denoiser.h"

#include "methods/bmfr/detail.h"

#include "base/parallel.h"
#include "stages/demodulate.h"

#include <algorithm>
#include <utility>

namespace afn::bmfr {

void Denoiser::reset()
{
    m_hasHistory = false;
    m_taa.reset();
}

const Image& Denoiser::process(const Frame& f, const Reprojector& taps,
    const TemporalAccumulator& ta, Image& scratch, Image& irradiance)
{
    // Frame-size buffers (as few as possible): m_filtered and the TAA's output hold the histories
    // between frames, m_spare and the caller's `scratch` are free. Each frame: regression ->
    // `scratch`; second accumulation -> m_spare (the old m_filtered becomes the spare it reads);
    // remodulated radiance -> `scratch` (the regression is dead by then); TAA -> m_spare, which
    // becomes its history (stages/taa.h), m_spare getting the old history's buffer.
    Image& regressed = scratch;
    // Highlights far above the frame's level are fitted clamped, their excess added back to the
    // fit at their pixel (stages/highlight_bypass.h): one lamp pixel would bend a whole block's
    // regression.
    m_highlights.split(ta.color(), highlightLimit(ta.color(), m_settings.highlights));
    const Image& accumulated = m_highlights.clamped(ta.color(), 0);
    if (f.hasWorkMask()) {
        const WorkRegion region = WorkRegion::fromMask(f.work).dilated(kWorkMargin);
        regression(f, accumulated, m_settings, f.frameIndex, regressed, &region);
    } else {
        regression(f, accumulated, m_settings, f.frameIndex, regressed);
    }
    // Detail the fit cannot express, kept where it stands above the accumulation's noise
    // (detail.h); the result takes the irradiance's place (not read again).
    Image* fitted = &regressed;
    const bool detail = m_settings.detail == Settings::Detail::On
        || (m_settings.detail == Settings::Detail::Auto && m_settings.spp >= kDetailSpp);
    if (detail) {
        restoreDetail(accumulated, ta.historyLength(), ta.alphaMin(), ta.effectiveSamplesLimit(),
            regressed, irradiance);
        fitted = &irradiance;
    }
    m_highlights.addExcess(*fitted, [](int, int, int) { return 1.0f; });
    // Second accumulation with the TA's taps: alpha = max(1/len, secondAlphaMin), len after TA.
    std::swap(m_filtered, m_spare);
    const Image& prevFiltered = m_spare;
    m_filtered.resize(f.width, f.height, 3);
    const bool history = m_hasHistory && taps.hasHistory() && prevFiltered.width() == f.width
        && prevFiltered.height() == f.height;
    const Image& len = ta.historyLength();
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < f.width; ++x) {
                const float* c = fitted->at(x, y);
                float* o = m_filtered.at(x, y);
                float prev[3];
                const float ws
                    = history ? gatherHistory<3>(taps.taps(x, y), prevFiltered, prev) : 0.0f;
                const float n = len(x, y, 0);
                if (ws > 0.0f && n > 1.0f) {
                    const float a = std::max(1.0f / n, m_settings.secondAlphaMin);
                    for (int k = 0; k < 3; ++k)
                        o[k] = blendHistory(prev[k], c[k], a);
                } else {
                    for (int k = 0; k < 3; ++k)
                        o[k] = c[k];
                }
            }
    });
    m_hasHistory = true;
    Image& radiance = regressed; // the regression is not read again
    remodulate(f, m_filtered, radiance);
    if (!m_settings.taa)
        return radiance;
    return m_taa.apply(taps, radiance, m_settings.taaAlpha, m_spare, &ta.trust());
}

const ParamBinding<Settings>& settingsBinding()
{
    using S = Settings;
    static const ParamBinding<S> binding
        = ParamBinding<S>()
              .add(&S::secondAlphaMin, "secondAlphaMin", 0.0, 1.0, "Second minimum blend factor",
                  "minimum weight of the regression output in the second accumulation "
                  "(BMFR SECOND_BLEND_ALPHA 0.1)")
              .add(&S::blockSize, "blockSize", 8, 64, "Block size",
                  "edge of the square regression blocks in pixels (BMFR: 32 only)")
              .add(&S::noise, "noise", 0.0, 1.0, "Feature noise",
                  "amplitude of the uniform noise added to the scaled features against singular "
                  "fits (BMFR NOISE_AMOUNT 0.01)")
              .add(&S::detail, "detail",
                  { { "auto", Settings::Detail::Auto }, { "off", Settings::Detail::Off },
                      { "on", Settings::Detail::On } },
                  "Keep detail",
                  "keep the accumulated colour's detail where it stands above its estimated noise "
                  "(a Wiener shrinkage of the fit's residual; methods/bmfr/detail.cpp); auto: on "
                  "from 4 spp (the spp parameter). off: BMFR as published, whose fit removes more "
                  "detail than noise from 16 spp on")
              .add(&S::highlights, "highlights", 0.0, 1e6, "Highlight bypass",
                  "values of the accumulated colour above this factor times the frame's bright "
                  "level (the power of two above its 99th percentile) skip the regression: it "
                  "fits them clamped and the excess is added back at its own pixel, so a small "
                  "light or glint stays a point instead of bending its block's fit; not in "
                  "BMFR; 0 = off")
              .add(&S::taa, "taa", "TAA", "apply BMFR's final temporal anti-aliasing")
              .add(&S::taaAlpha, "taaAlpha", 0.0, 1.0, "TAA blend factor",
                  "weight of the current frame in the TAA blend (BMFR 0.2)");
    return binding;
}

} // namespace afn::bmfr
