// SPDX-License-Identifier: Apache-2.0
// BMFR temporal accumulation (see stages/temporal_accumulation.h).
#include "stages/temporal_accumulation.h"

#include "base/parallel.h"

#include <algorithm>
#include <utility>

namespace afn {

const ParamBinding<AccumulationSettings>& accumulationBinding()
{
    static const ParamBinding<AccumulationSettings> binding
        = ParamBinding<AccumulationSettings>().add(&AccumulationSettings::alphaMin, "alphaMin", 0.0,
            1.0, "Minimum blend factor",
            "temporal accumulation: weight of the current frame once the history is long "
            "(BMFR BLEND_ALPHA 0.2)");
    return binding;
}

void TemporalAccumulator::reset()
{
    m_hasHistory = false;
}

void TemporalAccumulator::accumulate(const Reprojector& taps, const Image& irr)
{
    const int w = irr.width(), h = irr.height();
    std::swap(m_color, m_prevColor);
    std::swap(m_spp, m_prevSpp);
    m_color.resize(w, h, 3);
    m_spp.resize(w, h, 1);
    const bool history = m_hasHistory && taps.hasHistory() && m_prevColor.width() == w
        && m_prevColor.height() == h;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const bool identity = history && taps.identityRow(y);
            const float* c = irr.at(0, y);
            float* acc = m_color.at(0, y);
            float* spp = m_spp.at(0, y);
            for (int x = 0; x < w; ++x, c += 3, acc += 3) {
                float prev[3], sppS = 0.0f, ws = 0.0f;
                if (identity && taps.ownPixelAccepted(x, y)) {
                    // A static camera's row, own pixel accepted: its previous value, no decoding.
                    const float* p = m_prevColor.at(x, y);
                    for (int k = 0; k < 3; ++k)
                        prev[k] = p[k];
                    sppS = m_prevSpp(x, y, 0);
                    ws = 1.0f;
                } else if (history) {
                    const PixelTaps& t = taps.taps(x, y);
                    ws = gatherHistory<3>(t, m_prevColor, prev);
                    gatherHistory<1>(t, m_prevSpp, &sppS);
                }
                if (ws > 0.0f) {
                    const float alpha = std::max(1.0f / (sppS + 1.0f), m_alphaMin);
                    for (int k = 0; k < 3; ++k)
                        acc[k] = blendHistory(prev[k], c[k], alpha);
                    spp[x] = alpha < 1.0f ? std::min(sppS + 1.0f, kMaxHistoryLength) : 1.0f;
                } else {
                    for (int k = 0; k < 3; ++k)
                        acc[k] = c[k];
                    spp[x] = 1.0f;
                }
            }
        }
    });
    m_hasHistory = true;
}

} // namespace afn
