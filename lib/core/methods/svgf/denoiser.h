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
//      (Falcor). Not in the paper (`spread`, on below 4 spp): each such pixel's luminance term is
//      scaled by 1 - r, r the sparse share of its neighbourhood (kernels.h sparseShare: 0 at a
//      coefficient of variation of 1, 1 from 3, from the 7x7 moments with the guide's weights
//      only). At 1 spp a dark scene's first frame, or the frame after a light switches, is a
//      few bright samples among black pixels: the paper's luminance weights keep each bright
//      sample to itself and each black pixel black, so svgf put out a dark frame speckled with
//      white dots (`room-1000000`: 24 % of its pixels off by more than 0.25 tone-mapped, 4.9 %
//      with the spread; docs/afn-evaluation.md). Normalised bilateral weights cannot average
//      such samples without bias; the guide's weights alone can. Where the neighbourhood varies
//      like an image (edges, gradients: cv below 1) the paper's estimate is kept;
//   4. à-trous: 5x5 B3-spline taps h = (1/16, 1/4, 3/8, 1/4, 1/16), step 2^i, weights of
//      methods/svgf/guide.h with phiL = sigmaL * sqrt(g3x3(var)) + 1e-10; variance filtered with
//      squared weights; the output of iteration feedbackTap is the next frame's colour history.
// Filtered values are written as c_p + sum(w (c_q - c_p)) / sum(w), identical in exact arithmetic
// to sum(w c_q) / sum(w), so a constant image stays bit-exactly constant. The variance estimate and
// the à-trous passes run 8 pixels at a time on planes (methods/svgf/kernels.h), the à-trous passes
// 16 at a time with AVX-512 where the CPU has it (atrous_avx512.cpp); phiL is computed inside the
// pass. Colour, moments and history length are kept in the integration's planes, which are the
// next frame's history, gathered through the reprojection's taps once per pixel (all six values
// per tap; stages/reproject.h gatherHistoryWith).
// Work skipping (Frame::work, methods/svgf/work_skip.cpp): the variance estimate and the à-trous
// passes run only on the work region dilated by what the later passes read; the other pixels put
// out the temporally integrated colour.
#pragma once

#include "filter/work_region.h"
#include "methods/svgf/guide.h"
#include "methods/svgf/planes.h"
#include "stages/history_trust.h"
#include "stages/reproject.h"

#include <vector>

namespace afn::svgf {

class Denoiser {
public:
    void setSettings(const Settings& s) { m_settings = s; }
    void reset();
    /// Filter demodulated `irradiance` (3 ch) of frame `f`, reprojected by `taps` (bilinear with
    /// SVGF's box fallback), into `filtered` (3 ch, demodulated), which may be `irradiance` itself
    /// (it is read only by the temporal integration, before `filtered` is written).
    void process(const Frame& f, const Image& irradiance, const Reprojector& taps, Image& filtered);
    /// This frame's temporal integration (kernels.h IntegratedPlane; its colour planes the
    /// feedback iteration's output): for tests.
    const Planes& integrated() const { return m_integrated; }
    void setTrustSettings(const HistoryTrustSettings& s) { m_trust.setSettings(s); }
    /// The history trust of the last integration (stages/history_trust.h).
    const HistoryTrust& trust() const { return m_trust; }

    /// Pixels of the last frame whose highlight bypassed the filter (stages/highlight_bypass.h).
    std::int64_t highlightPixels() const { return m_highlights.pixels(); }

private:
    void integrate(const Image& irradiance, const Reprojector& taps);
    /// The highlight bypass (stages/highlight_bypass.h) on the integrated colour: split and
    /// clamp in place; then its excess added to `filtered` and to the next history.
    void clampHighlights();
    void restoreHighlights(Image& filtered);
    /// The history of rows [y0, y1) gathered into this frame's planes (length kNoHistory where
    /// none), except a static camera's own pixels, and added to the trust (temporal.cpp).
    void gatherRows(const Image& irradiance, const Reprojector& taps, int y0, int y1);
    void estimateVariance(const WorkRegion* region);
    void atrous(const Planes& in, Planes& out, int step, const WorkRegion* region);
    /// The regions the passes compute for this frame's work mask (work_skip.cpp); false when
    /// every pixel needs work.
    bool planRegions(const Frame& f);
    /// Copy colour planes into `dst` (3 ch) over `region` (null: everywhere).
    static void copyColor(const Planes& src, int firstPlane, const WorkRegion* region, Image& dst);
    /// Copy 3 colour planes into planes firstDst.. of `dst` over `region` (null: everywhere).
    static void copyPlanes(
        const Planes& src, int firstPlane, const WorkRegion* region, Planes& dst, int firstDst);

    Settings m_settings;
    Guide m_guide;
    HistoryTrust m_trust;
    HighlightBypass m_highlights; ///< this frame's
    bool m_hasHistory = false;
    /// This frame's integration (kernels.h IntegratedPlane), which is also the next frame's
    /// history: colour (the feedback iteration's output), moments l and l^2, history length; and
    /// the previous frame's, the à-trous ping-pong once this frame's is made (temporal.cpp).
    Planes m_integrated, m_prevIntegrated;
    Planes m_cv; ///< colour, variance, luminance (kernels.h ColorPlane), the variance's output
    std::vector<int> m_rowOrder; ///< à-trous rows by y mod step (kernels.h AtrousArgs)
    WorkRegion m_work; ///< pixels that need denoising (bounding spans of Frame::work)
    std::vector<WorkRegion> m_passRegions; ///< per à-trous iteration, the pixels it computes
    WorkRegion m_varianceRegion; ///< the pixels the variance estimate computes
};

} // namespace afn::svgf
