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
    std::swap(m_color, m_prevColor);
    std::swap(m_moments, m_prevMoments);
    std::swap(m_len, m_prevLen);
    m_color.resize(w, h, 3);
    m_moments.resize(w, h, 2);
    m_len.resize(w, h, 1);
    m_integrated.resize(w, h, kIntegratedPlanes);
    const bool history = m_hasHistory && taps.hasHistory() && m_prevColor.width() == w
        && m_prevColor.height() == h;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* c = irr.at(x, y);
                const float l = luminance(c);
                const float m[2] = { l, l * l };
                float pc[3], pm[2], plen = 0.0f, ws = 0.0f;
                if (history) {
                    const PixelTaps& t = taps.taps(x, y);
                    ws = gatherHistory<3>(t, m_prevColor, pc);
                    gatherHistory<2>(t, m_prevMoments, pm);
                    gatherHistory<1>(t, m_prevLen, &plen);
                }
                float* oc = m_color.at(x, y);
                float* om = m_moments.at(x, y);
                if (ws > 0.0f) {
                    const float len = std::min(plen + 1.0f, 255.0f);
                    const float a = std::max(m_settings.alpha, 1.0f / len);
                    const float am = std::max(m_settings.momentsAlpha, 1.0f / len);
                    for (int k = 0; k < 3; ++k)
                        oc[k] = blendHistory(pc[k], c[k], a);
                    for (int k = 0; k < 2; ++k)
                        om[k] = blendHistory(pm[k], m[k], am);
                    m_len(x, y, 0) = len;
                } else {
                    for (int k = 0; k < 3; ++k)
                        oc[k] = c[k];
                    om[0] = m[0];
                    om[1] = m[1];
                    m_len(x, y, 0) = 1.0f;
                }
                for (int k = 0; k < 3; ++k)
                    m_integrated.row(kIntRed + k, y)[x] = oc[k];
                m_integrated.row(kIntLuminance, y)[x] = luminance(oc);
                m_integrated.row(kMoment1, y)[x] = om[0];
                m_integrated.row(kMoment2, y)[x] = om[1];
                m_integrated.row(kHistoryLength, y)[x] = m_len(x, y, 0);
            }
    });
    m_hasHistory = true;
}

void Denoiser::estimateVariance(const WorkRegion* region)
{
    const int w = m_color.width(), h = m_color.height();
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
    // m_color is the feedback slot (it becomes the history in the next integrate()): it keeps the
    // unfiltered integrated colour unless iteration feedbackTap overwrites it (with skipping: over
    // the pixels that iteration computed, exact ones only).
    for (int i = 0; i < m_settings.iterations; ++i) {
        const WorkRegion* region = skip ? &m_passRegions[i] : nullptr;
        atrous(m_cv, m_cvTmp, 1 << i, region);
        std::swap(m_cv, m_cvTmp);
        if (i == m_settings.feedbackTap)
            copyColor(m_cv, kRed, region, m_color);
    }
    filtered.resize(f.width, f.height, 3);
    if (skip) // the cheap path: the temporally integrated colour, then the work region's result
        copyColor(m_integrated, kIntRed, nullptr, filtered);
    copyColor(m_cv, kRed, skip ? &m_work : nullptr, filtered);
}

} // namespace afn::svgf
