// SPDX-License-Identifier: Apache-2.0
// SVGF temporal integration, spatial variance estimate and per-frame driver (see
// methods/svgf/denoiser.h).
#include "methods/svgf/denoiser.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "methods/svgf/integrate_avx512.h"
#include "methods/svgf/kernels.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace afn::svgf {

void Denoiser::reset()
{
    m_hasHistory = false;
}

namespace {

/// The history's channels (colour, moments l and l^2, history length) in the integrated planes.
constexpr int kHistoryPlanes[]
    = { kIntRed, kIntGreen, kIntBlue, kMoment1, kMoment2, kHistoryLength };
constexpr int kHistoryChannels = 6;
/// Add a pixel to the history trust's block sums. svgf's colour history is its first à-trous
/// output, whose blur moves light between blocks: the trust would read that as change. The
/// history's colour is therefore scaled to the luminance of the unfiltered history (the first
/// moment), so the test sees the unfiltered brightness and the filtered chromaticity.
void addToTrust(HistoryTrust::RowAdder& trust, int x, const float* c, const float* prev)
{
    const float l = luminance(prev);
    const float s = l > 0.0f ? prev[3] / l : 1.0f;
    const float h[3] = { prev[0] * s, prev[1] * s, prev[2] * s };
    trust.add(x, c, h);
}

/// History length marking a pixel without history between gatherRows() and the blend.
constexpr float kNoHistory = -1.0f;

} // namespace

void Denoiser::integrate(const Image& irr, const Reprojector& taps)
{
    const int w = irr.width(), h = irr.height();
    std::swap(m_integrated, m_prevIntegrated);
    m_integrated.resize(w, h, kIntegratedPlanes);
    const bool history = m_hasHistory && taps.hasHistory() && m_prevIntegrated.width() == w
        && m_prevIntegrated.height() == h && m_prevIntegrated.count() == kIntegratedPlanes;
    const Planes& prevPlanes = m_prevIntegrated;
    // Two passes for the history trust (stages/history_trust.h), as the shared accumulation:
    // gather each pixel's history into this frame's planes (a static camera's own pixels are read
    // in place later) and add it to the trust's blocks; then blend with the trust.
    m_trust.begin(w, h, history);
    if (history)
        parallelRows(h, [&](int y0, int y1) { gatherRows(irr, taps, y0, y1); });
    m_trust.finish();
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    parallelRows(h, [&](int y0, int y1) {
        const float* prevRow[kHistoryChannels] = {};
        for (int y = y0; y < y1; ++y) {
            const bool identity = history && taps.identityRow(y);
            const float* trustRow = m_trust.rowTrust(y);
            const bool partial = trustRow != nullptr;
            float* planes[kIntegratedPlanes];
            for (int k = 0; k < kIntegratedPlanes; ++k)
                planes[k] = m_integrated.row(k, y);
            if (history)
                for (int k = 0; k < kHistoryChannels; ++k)
                    prevRow[k] = prevPlanes.row(kHistoryPlanes[k], y);
            auto pixel = [&](int x) {
                const float* c = irr.at(x, y);
                const float l = luminance(c);
                const float m[2] = { l, l * l };
                float prev[kHistoryChannels];
                bool has = false;
                if (identity && taps.ownPixelAccepted(x, y)) { // the gather's result, undecoded
                    for (int k = 0; k < kHistoryChannels; ++k)
                        prev[k] = prevRow[k][x];
                    has = true;
                } else if (history && planes[kHistoryLength][x] != kNoHistory) {
                    for (int k = 0; k < kHistoryChannels; ++k)
                        prev[k] = planes[kHistoryPlanes[k]][x]; // gathered by gatherRows()
                    has = true;
                }
                float o[kHistoryChannels];
                if (has) {
                    float len = std::min(prev[5] + 1.0f, 255.0f);
                    float a = std::max(m_settings.alpha, 1.0f / len);
                    float am = std::max(m_settings.momentsAlpha, 1.0f / len);
                    if (partial && trustRow[x] < 1.0f) { // history trust
                        const float cut = 1.0f - trustRow[x];
                        a += (1.0f - a) * cut;
                        am += (1.0f - am) * cut;
                        // Whole frames, rounded up: the length decides the spatial variance
                        // fallback (fewer than varianceHistory frames), which a slight cut
                        // should not trigger.
                        len = std::min(std::ceil(prev[5] * trustRow[x]) + 1.0f, 255.0f);
                    }
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
                for (int k = 0; k < kHistoryChannels; ++k)
                    planes[kHistoryPlanes[k]][x] = o[k];
                planes[kIntLuminance][x] = luminance(o);
            };
            int x = 0;
            if (identity && avx512) {
                // 16 pixels at a time where all 16 took their own previous pixel (the same
                // operations, methods/svgf/integrate_avx512.h); any other block per pixel.
                const float* prev16[kHistoryChannels];
                float* out16[kHistoryChannels + 1];
                for (; x + 16 <= w; x += 16) {
                    if (taps.ownPixelsAccepted16(x, y) != 0xFFFFu) {
                        for (int i = x; i < x + 16; ++i)
                            pixel(i);
                        continue;
                    }
                    for (int k = 0; k < kHistoryChannels; ++k) {
                        prev16[k] = prevRow[k] + x;
                        out16[k] = planes[kHistoryPlanes[k]] + x;
                    }
                    out16[kHistoryChannels] = planes[kIntLuminance] + x;
                    integrateOwnHistory16(irr.at(x, y), prev16, m_settings.alpha,
                        m_settings.momentsAlpha, partial ? trustRow + x : nullptr, out16);
                }
            }
            for (; x < w; ++x)
                pixel(x);
        }
    });
    m_hasHistory = true;
}

void Denoiser::gatherRows(const Image& irr, const Reprojector& taps, int y0, int y1)
{
    const int w = irr.width();
    const Planes& prevPlanes = m_prevIntegrated;
    auto load = [&](int x, int y, float* v) {
        for (int k = 0; k < kHistoryChannels; ++k)
            v[k] = prevPlanes.row(kHistoryPlanes[k], y)[x];
    };
    const bool measure = m_trust.enabled();
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    for (int y = y0; y < y1; ++y) {
        const bool identity = taps.identityRow(y);
        float* planes[kHistoryChannels];
        for (int k = 0; k < kHistoryChannels; ++k)
            planes[k] = m_integrated.row(kHistoryPlanes[k], y);
        HistoryTrust::RowAdder trust(measure ? m_trust.rowSums(y) : nullptr);
        auto pixel = [&](int x) {
            float prev[kHistoryChannels];
            if (identity && taps.ownPixelAccepted(x, y)) {
                if (measure) {
                    load(x, y, prev);
                    addToTrust(trust, x, irr.at(x, y), prev);
                }
                return;
            }
            if (!(gatherHistoryWith<kHistoryChannels>(taps.taps(x, y), load, prev) > 0.0f)) {
                planes[5][x] = kNoHistory;
                return;
            }
            for (int k = 0; k < kHistoryChannels; ++k)
                planes[k][x] = prev[k];
            if (measure)
                addToTrust(trust, x, irr.at(x, y), prev);
        };
        int x = 0;
        if (identity && measure && avx512) {
            // Two whole trust blocks at a time where all 16 pixels took their own previous pixel
            // (the same sums, methods/svgf/integrate_avx512.h); any other run per pixel.
            const float* prevRow[4]; // colour and moment 1
            for (int k = 0; k < 4; ++k)
                prevRow[k] = prevPlanes.row(kHistoryPlanes[k], y);
            for (; x + 16 <= w; x += 16) {
                if (taps.ownPixelsAccepted16(x, y) != 0xFFFFu) {
                    for (int i = x; i < x + 16; ++i)
                        pixel(i);
                    continue;
                }
                const float* prev16[4];
                for (int k = 0; k < 4; ++k)
                    prev16[k] = prevRow[k] + x;
                addOwnTrust16(irr.at(x, y), prev16, trust.wholeBlocks16(x));
            }
        }
        for (; x < w; ++x)
            pixel(x);
    }
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
    a.spread = spreadsSparseSamples(m_settings);
    a.region = region;
    parallelRows(h, [&](int y0, int y1) { varianceRows(a, y0, y1); });
}

void Denoiser::process(const Frame& f, const Image& irr, const Reprojector& taps, Image& filtered)
{
    m_guide.build(f, m_settings);
    integrate(irr, taps);
    clampHighlights();
    const bool skip = planRegions(f);
    estimateVariance(skip ? &m_varianceRegion : nullptr);
    filtered.resize(f.width, f.height, 3); // may be `irr`, which is not read again
    if (skip) // the cheap path: the temporally integrated colour (before the feedback below)
        copyColor(m_integrated, kIntRed, nullptr, filtered);
    // The à-trous ping-pong: m_cv and the previous frame's integration, which nothing reads once
    // this frame's is made (to save memory: no frame-size buffer of its own); its pads are zero as
    // every kernel writes in-image pixels only. m_integrated's colour planes are the feedback
    // slot (the history of the next integrate()): they keep the unfiltered integrated colour
    // unless iteration feedbackTap overwrites them (with skipping: over the pixels that
    // iteration computed, exact ones only).
    m_prevIntegrated.resize(f.width, f.height, kIntegratedPlanes);
    Planes* in = &m_cv;
    Planes* out = &m_prevIntegrated;
    for (int i = 0; i < m_settings.iterations; ++i) {
        const WorkRegion* region = skip ? &m_passRegions[i] : nullptr;
        atrous(*in, *out, 1 << i, region);
        std::swap(in, out);
        if (i == m_settings.feedbackTap)
            copyPlanes(*in, kRed, region, m_integrated, kIntRed);
    }
    copyColor(*in, kRed, skip ? &m_work : nullptr, filtered);
    restoreHighlights(filtered);
}

void Denoiser::clampHighlights()
{
    Planes& p = m_integrated;
    const int w = p.width(), h = p.height();
    const float limit = highlightLimit(w, h, m_settings.highlights, [&](int x, int y) {
        return std::max({ p.row(kIntRed, y)[x], p.row(kIntGreen, y)[x], p.row(kIntBlue, y)[x] });
    });
    m_highlights.split(w, h, limit, [&](int x, int y, int k) { return p.row(kIntRed + k, y)[x]; });
    m_highlights.forEach([&](int x, int y, const float*) {
        float c[3];
        for (int k = 0; k < 3; ++k)
            c[k] = p.row(kIntRed + k, y)[x] = std::min(p.row(kIntRed + k, y)[x], limit);
        p.row(kIntLuminance, y)[x] = luminance(c); // the edge-stopping's, as integrate() writes
    });
}

void Denoiser::restoreHighlights(Image& filtered)
{
    // The output and the next history (the feedback iteration's output, or the clamped
    // integrated colour itself) get the excess back at its pixel.
    m_highlights.forEach([&](int x, int y, const float* e) {
        for (int k = 0; k < 3; ++k) {
            filtered(x, y, k) += e[k];
            m_integrated.row(kIntRed + k, y)[x] += e[k];
        }
    });
}

} // namespace afn::svgf
