// SPDX-License-Identifier: Apache-2.0
// BMFR temporal accumulation (see stages/temporal_accumulation.h).
#include "stages/temporal_accumulation.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "stages/temporal_accumulation_avx512.h"

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

void TemporalAccumulator::begin(const Reprojector& taps, int w, int h)
{
    std::swap(m_color, m_prevColor);
    std::swap(m_spp, m_prevSpp);
    m_color.resize(w, h, 3);
    m_spp.resize(w, h, 1);
    m_history = m_hasHistory && taps.hasHistory() && m_prevColor.width() == w
        && m_prevColor.height() == h;
    m_trust.begin(w, h, m_history);
}

void TemporalAccumulator::accumulate(const Reprojector& taps, const Image& irr)
{
    begin(taps, irr.width(), irr.height());
    parallelRows(irr.height(), [&](int y0, int y1) { gatherRows(taps, irr, y0, y1); });
    finishTrust();
    parallelRows(irr.height(), [&](int y0, int y1) { blendRows(taps, irr, y0, y1); });
    end();
}

namespace {

/// History length marking a pixel without history between gatherRows() and blendRows().
constexpr float kNoHistory = -1.0f;

} // namespace

void TemporalAccumulator::blendPixel(
    const float* c, const float* prev, float prevSpp, float trust, float* acc, float* spp) const
{
    float sppS = prevSpp;
    float alpha = std::max(1.0f / (sppS + 1.0f), m_alphaMin);
    if (trust < 1.0f) { // history trust (stages/history_trust.h)
        alpha += (1.0f - alpha) * (1.0f - trust);
        sppS *= trust;
    }
    for (int k = 0; k < 3; ++k)
        acc[k] = blendHistory(prev[k], c[k], alpha);
    *spp = alpha < 1.0f ? std::min(sppS + 1.0f, kMaxHistoryLength) : 1.0f;
}

void TemporalAccumulator::gatherRows(const Reprojector& taps, const Image& irr, int y0, int y1)
{
    if (!m_history) {
        for (int y = y0; y < y1; ++y)
            std::fill(m_spp.at(0, y), m_spp.at(0, y) + irr.width(), kNoHistory);
        return;
    }
    const int w = irr.width();
    const bool measure = m_trust.enabled();
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    for (int y = y0; y < y1; ++y) {
        const bool identity = taps.identityRow(y);
        const float* c = irr.at(0, y);
        float* acc = m_color.at(0, y);
        float* spp = m_spp.at(0, y);
        HistoryTrust::RowAdder trust(measure ? m_trust.rowSums(y) : nullptr);
        auto pixel = [&](int x) {
            if (identity && taps.ownPixelAccepted(x, y)) {
                // A static camera's row, own pixel accepted: blended here with trust 1 while
                // its history is in cache; blendRows() blends it again where the trust is lower.
                const float* prev = m_prevColor.at(x, y);
                if (measure)
                    trust.add(x, c + 3 * x, prev);
                blendPixel(c + 3 * x, prev, m_prevSpp(x, y, 0), 1.0f, acc + 3 * x, spp + x);
                return;
            }
            const PixelTaps& t = taps.taps(x, y);
            float* prev = acc + 3 * x;
            const float ws = gatherHistory<3>(t, m_prevColor, prev);
            if (!(ws > 0.0f)) {
                spp[x] = kNoHistory;
                return;
            }
            gatherHistory<1>(t, m_prevSpp, spp + x);
            if (measure)
                trust.add(x, c + 3 * x, prev);
        };
        int x = 0;
        if (identity && avx512)
            // 16 pixels at a time where all 16 took their own previous pixel: two whole trust
            // blocks and the blend with trust 1 (the same sums and values,
            // stages/temporal_accumulation_avx512.h); any other run per pixel.
            for (; x + 16 <= w; x += 16) {
                if (taps.ownPixelsAccepted16(x, y) == 0xFFFFu) {
                    const float* prev = m_prevColor.at(x, y);
                    if (measure)
                        addOwnHistoryTrust16(c + 3 * x, prev, trust.wholeBlocks16(x));
                    blendOwnHistory16(c + 3 * x, prev, &m_prevSpp(x, y, 0), m_alphaMin, nullptr,
                        acc + 3 * x, spp + x);
                } else {
                    for (int i = x; i < x + 16; ++i)
                        pixel(i);
                }
            }
        for (; x < w; ++x)
            pixel(x);
    }
}

void TemporalAccumulator::blendRows(const Reprojector& taps, const Image& irr, int y0, int y1)
{
    const int w = irr.width();
    const bool history = m_history;
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    for (int y = y0; y < y1; ++y) {
        const bool identity = history && taps.identityRow(y);
        const float* trustRow = m_trust.rowTrust(y);
        const bool partial = trustRow != nullptr;
        const float* c = irr.at(0, y);
        float* acc = m_color.at(0, y);
        float* spp = m_spp.at(0, y);
        auto pixel = [&](int x) {
            float* a = acc + 3 * x;
            const float* cx = c + 3 * x;
            const float t = partial ? trustRow[x] : 1.0f;
            if (identity && taps.ownPixelAccepted(x, y)) {
                // Blended by gatherRows() with trust 1; again from the history where it is lower.
                if (t < 1.0f)
                    blendPixel(cx, m_prevColor.at(x, y), m_prevSpp(x, y, 0), t, a, spp + x);
                return;
            }
            if (spp[x] == kNoHistory) {
                for (int k = 0; k < 3; ++k)
                    a[k] = cx[k];
                spp[x] = 1.0f;
                return;
            }
            const float prev[3] = { a[0], a[1], a[2] };
            blendPixel(cx, prev, spp[x], t, a, spp + x);
        };
        int x = 0;
        if (identity && avx512)
            // 16 pixels at a time where all 16 took their own previous pixel: nothing left to do
            // at trust 1, else blended again with the row's trust (the same operations,
            // stages/temporal_accumulation_avx512.h); any other block per pixel.
            for (; x + 16 <= w; x += 16) {
                if (taps.ownPixelsAccepted16(x, y) == 0xFFFFu) {
                    if (partial)
                        blendOwnHistory16(c + 3 * x, m_prevColor.at(x, y), &m_prevSpp(x, y, 0),
                            m_alphaMin, trustRow + x, acc + 3 * x, spp + x);
                } else {
                    for (int i = x; i < x + 16; ++i)
                        pixel(i);
                }
            }
        for (; x < w; ++x)
            pixel(x);
    }
}

} // namespace afn
