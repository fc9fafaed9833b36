// SPDX-License-Identifier: Apache-2.0
// SVGF temporal integration, spatial variance estimate and per-frame driver (see
// methods/svgf/denoiser.h).
#include "methods/svgf/denoiser.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "methods/svgf/integrate_avx512.h"
#include "methods/svgf/kernels.h"

#include <algorithm>
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

} // namespace

void Denoiser::integrate(const Image& irr, const Reprojector& taps)
{
    const int w = irr.width(), h = irr.height();
    std::swap(m_integrated, m_prevIntegrated);
    m_integrated.resize(w, h, kIntegratedPlanes);
    const bool history = m_hasHistory && taps.hasHistory() && m_prevIntegrated.width() == w
        && m_prevIntegrated.height() == h && m_prevIntegrated.count() == kIntegratedPlanes;
    const Planes& prevPlanes = m_prevIntegrated;
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    parallelRows(h, [&](int y0, int y1) {
        const float* prevRow[kHistoryChannels] = {};
        auto load = [&](int x, int y, float* v) {
            for (int k = 0; k < kHistoryChannels; ++k)
                v[k] = prevPlanes.row(kHistoryPlanes[k], y)[x];
        };
        for (int y = y0; y < y1; ++y) {
            const bool identity = history && taps.identityRow(y);
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
                // Colour, moments and length share the taps: one renormalised gather of all six.
                float prev[kHistoryChannels];
                float ws = 0.0f;
                if (identity && taps.ownPixelAccepted(x, y)) { // the gather's result, undecoded
                    for (int k = 0; k < kHistoryChannels; ++k)
                        prev[k] = prevRow[k][x];
                    ws = 1.0f;
                } else if (history) {
                    ws = gatherHistoryWith<kHistoryChannels>(taps.taps(x, y), load, prev);
                }
                float o[kHistoryChannels];
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
                    integrateOwnHistory16(
                        irr.at(x, y), prev16, m_settings.alpha, m_settings.momentsAlpha, out16);
                }
            }
            for (; x < w; ++x)
                pixel(x);
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
}

} // namespace afn::svgf
