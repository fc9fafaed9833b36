// SPDX-License-Identifier: Apache-2.0
// One SVGF à-trous iteration on colour + variance (see methods/svgf/denoiser.h).
#include "methods/svgf/denoiser.h"

#include "base/parallel.h"

#include <algorithm>

namespace afn::svgf {

namespace {

constexpr float kMaxExponent = 40.0f; ///< taps with exp(-e) below exp(-40) are skipped
constexpr float kB3[3] = { 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f }; ///< by |offset|

/// 3x3 Gaussian of the variance channel (1/4 centre, 1/8 edges, 1/16 corners), in-image taps.
float blurredVariance(const Image& cv, int x, int y)
{
    static constexpr float k[2] = { 0.5f, 0.25f };
    float sum = 0.0f, wsum = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= cv.width() || qy >= cv.height())
                continue;
            const float wq = (dx == 0 ? k[0] : k[1]) * (dy == 0 ? k[0] : k[1]);
            sum += wq * cv(qx, qy, 3);
            wsum += wq;
        }
    return sum / wsum;
}

} // namespace

void Denoiser::atrous(const Image& in, Image& out, int step) const
{
    const int w = in.width(), h = in.height();
    out.resize(w, h, 4);
    const float sigmaL = m_settings.sigmaL;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* cp = in.at(x, y);
                const float lp = luminance(cp);
                const float invPhiL = 1.0f
                    / (sigmaL * std::sqrt(std::max(0.0f, blurredVariance(in, x, y))) + 1e-10f);
                float ws = 0.0f, vsum = 0.0f, dc[3] = { 0, 0, 0 };
                for (int j = -2; j <= 2; ++j)
                    for (int i = -2; i <= 2; ++i) {
                        const int qx = x + i * step, qy = y + j * step;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h)
                            continue;
                        const float* cq = in.at(qx, qy);
                        float wq = kB3[std::abs(i)] * kB3[std::abs(j)];
                        if (i != 0 || j != 0) {
                            const float wn = m_guide.normalFactor(x, y, qx, qy);
                            const float e = m_guide.depthTerm(x, y, qx, qy, i * step, j * step)
                                + std::fabs(lp - luminance(cq)) * invPhiL;
                            // exp(-40) < 5e-18: such taps are negligible; skipping them saves the
                            // exp().
                            if (!(wn > 0.0f) || !(e < kMaxExponent))
                                continue;
                            wq *= std::exp(-e) * wn;
                        }
                        ws += wq;
                        vsum += wq * wq * cq[3];
                        for (int k = 0; k < 3; ++k)
                            dc[k] += wq * (cq[k] - cp[k]);
                    }
                float* o = out.at(x, y);
                const float inv = 1.0f / ws; // ws >= centre weight (3/8)^2 > 0
                for (int k = 0; k < 3; ++k)
                    o[k] = std::max(0.0f, cp[k] + dc[k] * inv);
                o[3] = vsum * inv * inv;
            }
    });
}

const ParamBinding<Settings>& settingsBinding()
{
    using S = Settings;
    static const ParamBinding<S> binding
        = ParamBinding<S>()
              .add(&S::iterations, "iterations", 0, 10, "À-trous iterations",
                  "number of 5x5 à-trous passes with step 2^i (paper 5, Falcor 4)")
              .add(&S::feedbackTap, "feedbackTap", -1, 9, "Feedback iteration",
                  "iteration whose output becomes the colour history (0 = first, as the paper; "
                  "-1 or >= iterations = unfiltered integrated colour; Falcor 1)")
              .add(&S::sigmaL, "sigmaL", 0.0, 1000.0, "Luminance sigma",
                  "luminance edge-stopping, in standard deviations of the local luminance "
                  "(paper 4, Falcor 10)")
              .add(&S::sigmaN, "sigmaN", 0.0, 1024.0, "Normal exponent",
                  "exponent of max(0, n.n') (paper and Falcor 128)")
              .add(&S::sigmaZ, "sigmaZ", 0.0, 1000.0, "Depth sigma",
                  "depth edge-stopping relative to the depth gradient (paper 1)")
              .add(&S::alpha, "alpha", 0.0, 1.0, "Colour blend factor",
                  "minimum weight of the current frame in the colour history (paper 0.2, "
                  "Falcor 0.05)")
              .add(&S::momentsAlpha, "momentsAlpha", 0.0, 1.0, "Moments blend factor",
                  "minimum weight of the current frame in the moments history (paper 0.2)")
              .add(&S::varianceHistory, "varianceHistory", 1, 255, "Spatial variance below",
                  "history length (frames) below which variance is estimated over 7x7 (paper 4)");
    return binding;
}

} // namespace afn::svgf
