// SPDX-License-Identifier: Apache-2.0
// BMFR per-frame pipeline: TA, regression, second accumulation, remodulation, TAA (see bmfr.h).
#include "methods/bmfr/denoiser.h"

#include "stages/demodulate.h"
#include "base/parallel.h"

#include <algorithm>
#include <utility>

namespace afn::bmfr {

void Denoiser::setSettings(const Settings& s, const ReprojectSettings& r)
{
    m_settings = s;
    ReprojectSettings rs = r;
    rs.boxFallback = false;
    m_reproject.setSettings(rs);
    m_ta.setAlphaMin(s.alphaMin);
}

void Denoiser::reset()
{
    m_reproject.reset();
    m_ta.reset();
    m_hasHistory = false;
}

void Denoiser::process(const Frame& f, const Image& irr, Image& out)
{
    if (f.frameIndex == 0)
        reset();
    m_reproject.compute(f);
    m_ta.accumulate(m_reproject, irr);
    regression(f, m_ta.color(), m_settings, f.frameIndex, m_regressed);

    // Second accumulation with the TA's taps: alpha = max(1/len, secondAlphaMin), len after TA.
    std::swap(m_filtered, m_prevFiltered);
    m_filtered.resize(f.width, f.height, 3);
    const bool history = m_hasHistory && m_reproject.hasHistory()
        && m_prevFiltered.width() == f.width && m_prevFiltered.height() == f.height;
    const Image& len = m_ta.historyLength();
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < f.width; ++x) {
                const float* c = m_regressed.at(x, y);
                float* o = m_filtered.at(x, y);
                float prev[3];
                const float ws = history
                    ? gatherHistory<3>(m_reproject.taps(x, y), m_prevFiltered, prev)
                    : 0.0f;
                const float n = len(x, y, 0);
                if (ws > 0.0f && n > 1.0f) {
                    const float a = std::max(1.0f / n, m_settings.secondAlphaMin);
                    for (int k = 0; k < 3; ++k)
                        o[k] = prev[k] + a * (c[k] - prev[k]);
                } else {
                    for (int k = 0; k < 3; ++k)
                        o[k] = c[k];
                }
            }
    });

    if (!m_settings.taa) {
        remodulate(f, m_filtered, out);
    } else {
        remodulate(f, m_filtered, m_radiance);
        taa(m_reproject, m_radiance, m_prevOutput, m_settings.taaAlpha, out);
        m_prevOutput = out;
    }
    m_reproject.storeGeometry(f);
    m_hasHistory = true;
}

std::vector<ParamDesc> bmfrParams()
{
    return {
        floatParam("alphaMin", 0.2, 0.0, 1.0, "TA minimum blend factor",
            "weight of the current frame in the first accumulation once the history is "
            "long (BMFR BLEND_ALPHA 0.2)"),
        floatParam("secondAlphaMin", 0.1, 0.0, 1.0, "Second minimum blend factor",
            "minimum weight of the regression output in the second accumulation "
            "(BMFR SECOND_BLEND_ALPHA 0.1)"),
        intParam("blockSize", 32, 8, 64, "Block size",
            "edge of the square regression blocks in pixels (BMFR: 32 only)"),
        floatParam("noise", 0.01, 0.0, 1.0, "Feature noise",
            "amplitude of the uniform noise added to the scaled features against singular "
            "fits (BMFR NOISE_AMOUNT 0.01)"),
        boolParam("taa", true, "TAA", "apply BMFR's final temporal anti-aliasing"),
        floatParam("taaAlpha", 0.2, 0.0, 1.0, "TAA blend factor",
            "weight of the current frame in the TAA blend (BMFR 0.2)"),
    };
}

Settings readBmfrSettings(const ParamSet& p)
{
    Settings s;
    s.alphaMin = p.getFloat("alphaMin");
    s.secondAlphaMin = p.getFloat("secondAlphaMin");
    s.blockSize = p.getInt("blockSize");
    s.noise = p.getFloat("noise");
    s.taa = p.getBool("taa");
    s.taaAlpha = p.getFloat("taaAlpha");
    return s;
}

} // namespace afn::bmfr
