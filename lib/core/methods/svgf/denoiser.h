// SPDX-License-Identifier: Apache-2.0
// Spatiotemporal variance-guided filtering (Schied et al., HPG 2017) on demodulated irradiance.
// Per frame:
//   1. reprojection with SVGF's 3x3 box fallback (stages/reproject.h acceptance tests);
//   2. temporal integration of colour and luminance moments (l, l^2) with
//      alpha = max(alpha, 1/len), alphaMoments = max(momentsAlpha, 1/len) (Falcor's cumulative
//      start; the paper's fixed 0.2 is reached after 5 frames); len = history length, 1 on
//      disocclusion;
//   3. variance = max(0, m2 - m1^2); while len < varianceHistory a 7x7 cross-bilateral estimate of
//      moments and colour replaces it (phiL = sigmaL, not variance-scaled), boosted by 4/len
//      (Falcor);
//   4. à-trous: 5x5 B3-spline taps h = (1/16, 1/4, 3/8, 1/4, 1/16), step 2^i, weights of
//      methods/svgf/guide.h with phiL = sigmaL * sqrt(g3x3(var)) + 1e-10; variance filtered with
//      squared weights; the output of iteration feedbackTap is the next frame's colour history.
// Filtered values are written as c_p + sum(w (c_q - c_p)) / sum(w), identical in exact arithmetic
// to sum(w c_q) / sum(w), so a constant image stays bit-exactly constant. The variance estimate and
// the à-trous passes run 8 pixels at a time on planes (methods/svgf/kernels.h), the à-trous passes
// 16 at a time with AVX-512 where the CPU has it (atrous_avx512.cpp); phiL is computed inside the
// pass. Colour, moments and history length are kept as one 6-channel history image, gathered
// through the reprojection's taps once per pixel.
#pragma once

#include "methods/svgf/guide.h"
#include "methods/svgf/planes.h"
#include "stages/reproject.h"

#include <vector>

namespace afn::svgf {

class Denoiser {
public:
    void setSettings(const Settings& s) { m_settings = s; }
    void reset();
    /// Filter demodulated `irradiance` (3 ch) of frame `f`, reprojected by `taps` (bilinear with
    /// SVGF's box fallback), into `filtered` (3 ch, demodulated).
    void process(const Frame& f, const Image& irradiance, const Reprojector& taps, Image& filtered);

private:
    void integrate(const Image& irradiance, const Reprojector& taps);
    void estimateVariance();
    void atrous(const Planes& in, Planes& out, int step);

    Settings m_settings;
    Guide m_guide;
    bool m_hasHistory = false;
    /// Channels of the history: colour (3; the feedback iteration's output), moments l and l^2,
    /// history length.
    static constexpr int kHistoryChannels = 6;
    Image m_history, m_prevHistory; ///< this frame's, the previous frame's
    Planes m_integrated; ///< this frame's integration as planes (kernels.h IntegratedPlane)
    Planes m_cv, m_cvTmp; ///< colour, variance, luminance ping-pong (kernels.h ColorPlane)
    std::vector<int> m_rowOrder; ///< à-trous rows by y mod step (kernels.h AtrousArgs)
};

} // namespace afn::svgf
