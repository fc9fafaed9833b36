// SPDX-License-Identifier: Apache-2.0
// SVGF temporal integration, spatial variance estimate and per-frame driver (see
// methods/svgf/denoiser.h).
#include "methods/svgf/denoiser.h"

#include "base/parallel.h"
#include "methods/svgf/kernels.h"

#include <algorithm>
#include <utility>

namespace afn::svgf {

void Denoiser::reset()
{
    m_hasHistory = false;
}

void Denoiser::integrate(const Image& irr, const Reprojector& taps)
{
    const int w = irr.width(), h = irr.height();
    std::swap(m_history, m_prevHistory);
    m_history.resize(w, h, kHistoryChannels);
    m_integrated.resize(w, h, kIntegratedPlanes);
    const bool history = m_hasHistory && taps.hasHistory() && m_prevHistory.width() == w
        && m_prevHistory.height() == h;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const bool identity = history && taps.identityRow(y);
            float* planes[kIntegratedPlanes];
            for (int k = 0; k < kIntegratedPlanes; ++k)
                planes[k] = m_integrated.row(k, y);
            for (int x = 0; x < w; ++x) {
                const float* c = irr.at(x, y);
                const float l = luminance(c);
                const float m[2] = { l, l * l };
                // Colour, moments and length share the taps: one renormalised gather of all six.
                float prev[kHistoryChannels];
                float ws = 0.0f;
                if (identity && taps.ownPixelAccepted(x, y)) { // the gather's result, undecoded
                    const float* p = m_prevHistory.at(x, y);
                    for (int k = 0; k < kHistoryChannels; ++k)
                        prev[k] = p[k];
                    ws = 1.0f;
                } else if (history) {
                    ws = gatherHistory<kHistoryChannels>(taps.taps(x, y), m_prevHistory, prev);
                }
                float* o = m_history.at(x, y);
                if (ws > 0.0f) {
                    const float len = std::min(prev[5] + 1.0f, 255.0f);
                    const float a = std::max(m_settings.alpha, 1.0f / len);
                    const float am = std::max(m_settings.momentsAlpha, 1.0f / len);
                    for (int k = 0; k < 3; ++k)
                        o[k] = blendHistory(prev[k], c[k], a);
                    for (int k = 0; k < 2; ++k)
                        o[3 + k] = blendHistory(prev[3 + k], m[k], am);
                    o[5] = len;
                } else {
                    for (int k = 0; k < 3; ++k)
                        o[k] = c[k];
                    o[3] = m[0];
                    o[4] = m[1];
                    o[5] = 1.0f;
                }
                for (int k = 0; k < 3; ++k)
                    planes[kIntRed + k][x] = o[k];
                planes[kIntLuminance][x] = luminance(o);
                planes[kMoment1][x] = o[3];
                planes[kMoment2][x] = o[4];
                planes[kHistoryLength][x] = o[5];
            }
        }
    });
    m_hasHistory = true;
}

void Denoiser::estimateVariance(const WorkRegion* region)
{
    const int w = m_integrated.width(), h = m_integrated.height();
    m_cv.resize(w, h, kColorPlanes);
    VarianceArgs a;
    a.in = &m_integrated;
    a.guide = &m_guide;
    a.out = &m_cv;
    a.phiL = m_settings.sigmaL;
    a.varianceHistory = static_cast<float>(m_settings.varianceHistory);
    a.region = region;
    parallelRows(h, [&](int y0, int y1) { varianceRows(a, y0, y1); });
}

void Denoiser::process(const Frame& f, const Image& irr, const Reprojector& taps, Image& filtered)
{
    m_guide.build(f, m_settings);
    integrate(irr, taps);
    const bool skip = planRegions(f);
    estimateVariance(skip ? &m_varianceRegion : nullptr);
    // m_history's colour is the feedback slot (the history of the next integrate()): it keeps the
    // unfiltered integrated colour unless iteration feedbackTap overwrites it (with skipping: over
    // the pixels that iteration computed, exact ones only).
    for (int i = 0; i < m_settings.iterations; ++i) {
        const WorkRegion* region = skip ? &m_passRegions[i] : nullptr;
        atrous(m_cv, m_cvTmp, 1 << i, region);
        std::swap(m_cv, m_cvTmp);
        if (i == m_settings.feedbackTap)
            copyColor(m_cv, kRed, region, m_history);
    }
    filtered.resize(f.width, f.height, 3);
    if (skip) // the cheap path: the temporally integrated colour, then the work region's result
        copyColor(m_integrated, kIntRed, nullptr, filtered);
    copyColor(m_cv, kRed, skip ? &m_work : nullptr, filtered);
}

} // namespace afn::svgf
