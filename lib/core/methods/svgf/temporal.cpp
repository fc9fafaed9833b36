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
            float* planes[kIntegratedPlanes];
            for (int k = 0; k < kIntegratedPlanes; ++k)
                planes[k] = m_integrated.row(k, y);
            for (int x = 0; x < w; ++x) {
                const float* c = irr.at(x, y);
                const float l = luminance(c);
                const float m[2] = { l, l * l };
                // Colour, moments and length share the taps: one renormalised gather of all six.
                float prev[kHistoryChannels];
                const float ws = history
                    ? gatherHistory<kHistoryChannels>(taps.taps(x, y), m_prevHistory, prev)
                    : 0.0f;
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

void Denoiser::estimateVariance()
{
    const int w = m_integrated.width(), h = m_integrated.height();
    m_cv.resize(w, h, kColorPlanes);
    VarianceArgs a;
    a.in = &m_integrated;
    a.guide = &m_guide;
    a.out = &m_cv;
    a.phiL = m_settings.sigmaL;
    a.varianceHistory = static_cast<float>(m_settings.varianceHistory);
    parallelRows(h, [&](int y0, int y1) { varianceRows(a, y0, y1); });
}

void Denoiser::process(const Frame& f, const Image& irr, const Reprojector& taps, Image& filtered)
{
    m_guide.build(f, m_settings);
    integrate(irr, taps);
    estimateVariance();
    // m_history's colour is the feedback slot (the history of the next integrate()): it keeps the
    // unfiltered integrated colour unless iteration feedbackTap overwrites it.
    for (int i = 0; i < m_settings.iterations; ++i) {
        atrous(m_cv, m_cvTmp, 1 << i);
        std::swap(m_cv, m_cvTmp);
        if (i == m_settings.feedbackTap) {
            const int w = m_cv.width(), h = m_cv.height();
            parallelRows(h, [&](int y0, int y1) {
                for (int y = y0; y < y1; ++y)
                    for (int k = 0; k < 3; ++k) {
                        const float* c = m_cv.row(kRed + k, y);
                        for (int x = 0; x < w; ++x)
                            m_history(x, y, k) = c[x];
                    }
            });
        }
    }
    filtered.resize(f.width, f.height, 3);
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int k = 0; k < 3; ++k) {
                const float* c = m_cv.row(kRed + k, y);
                for (int x = 0; x < f.width; ++x)
                    filtered(x, y, k) = c[x];
            }
    });
}

} // namespace afn::svgf
