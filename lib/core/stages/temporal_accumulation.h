// SPDX-License-Identifier: Apache-2.0
// Temporal accumulation exactly as BMFR (bmfr.cl accumulate_noisy_data), per pixel:
//   prev, spp_s = renormalised reprojected history (accepted bilinear taps, stages/reproject.h)
//   if sum(w) > 0: alpha = max(1 / (spp_s + 1), alphaMin), spp = min(spp_s + 1, 255)
//   else:          alpha = 1, spp = 1                       (disocclusion: history reset)
//   acc = prev + alpha * (colour - prev)
// The blend is written as a lerp from the history (BMFR: alpha*c + (1-alpha)*prev; identical in
// exact arithmetic) so that an unchanged value stays bit-exactly unchanged. spp is kept as a float
// capped at 255 (BMFR stores a uchar; the cap has no effect once alpha = alphaMin). Inputs are
// finite and non-negative (stages/demodulate.h), so the history never holds NaN/Inf.
//
// History trust (stages/history_trust.h): the accumulation runs in two passes over the rows.
// gatherRows() reprojects the history of each pixel into the output buffers and adds it to the
// trust's block statistics; a static camera's pixel that took its own previous pixel (most
// pixels of most shots) is blended there at once with trust 1, while its history is in cache.
// After HistoryTrust::finish(), blendRows() blends the reprojected pixels with
// alpha' = alpha + (1 - alpha) * (1 - t) and history length s * t + 1, and blends the own-pixel
// ones again from the history where t < 1 (t = 1: the arithmetic above, bit for bit; the
// previous frame's buffers are intact until the next frame).
#pragma once

#include "stages/history_trust.h"
#include "stages/reproject.h"

namespace afn {

/// Largest history length kept (BMFR's uchar).
constexpr float kMaxHistoryLength = 255.0f;

/// Settings of the accumulation.
struct AccumulationSettings {
    float alphaMin = 0.2f; ///< minimum blend factor (BMFR BLEND_ALPHA)
};

/// Descriptors of AccumulationSettings (in the table of every method that accumulates).
const ParamBinding<AccumulationSettings>& accumulationBinding();

/// Running per-pixel accumulation of demodulated colour.
class TemporalAccumulator {
public:
    void setSettings(const AccumulationSettings& s) { m_alphaMin = s.alphaMin; }
    void setTrustSettings(const HistoryTrustSettings& s) { m_trust.setSettings(s); }

    /// Blend `irradiance` (3 ch) into the history reprojected by `taps`.
    void accumulate(const Reprojector& taps, const Image& irradiance);
    /// accumulate() in steps, for callers that run it row band by row band with other per-row
    /// work (the Filter base: demodulation, remodulation): begin() once, then gatherRows() over
    /// every row exactly once (any order, any threads), finishTrust(), blendRows() over every row
    /// exactly once, then end(). The same values.
    void begin(const Reprojector& taps, int width, int height);
    void gatherRows(const Reprojector& taps, const Image& irradiance, int y0, int y1);
    void finishTrust() { m_trust.finish(); }
    void blendRows(const Reprojector& taps, const Image& irradiance, int y0, int y1);
    void end() { m_hasHistory = true; }
    void reset();

    /// The history trust of the last frame (stages/history_trust.h).
    const HistoryTrust& trust() const { return m_trust; }

    /// Accumulated colour of the last frame (3 ch).
    const Image& color() const { return m_color; }
    /// History length of the last frame (1 ch; 1 = reset this frame).
    const Image& historyLength() const { return m_spp; }
    /// The minimum blend factor (AccumulationSettings::alphaMin).
    float alphaMin() const { return m_alphaMin; }
    /// Samples whose plain mean has the variance a long history converges to: (2 - a) / a for the
    /// exponential average with blend a = alphaMin (9 at 0.2; infinite at 0, where the history
    /// is a plain mean for up to kMaxHistoryLength frames).
    float effectiveSamplesLimit() const
    {
        return m_alphaMin > 0.0f ? (2.0f - m_alphaMin) / m_alphaMin : kMaxHistoryLength;
    }
    /// The previous frame's colour buffer, which nothing reads until the next accumulate()
    /// overwrites it: scratch a method may use within the current frame (any shape; contents
    /// unspecified, not kept across frames). Lending it saves the method a frame-size image.
    Image& scratch() { return m_prevColor; }

private:
    /// The blend of one pixel with history colour `prev` and length `prevSpp` at trust `trust`
    /// (the file comment's arithmetic) into acc (3 floats) and *spp.
    void blendPixel(const float* c, const float* prev, float prevSpp, float trust, float* acc,
        float* spp) const;

    float m_alphaMin = 0.2f;
    bool m_hasHistory = false;
    bool m_history = false; ///< this frame blends with a history (set by begin())
    Image m_color, m_spp, m_prevColor, m_prevSpp;
    HistoryTrust m_trust;
};

} // namespace afn
