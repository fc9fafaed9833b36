// SPDX-License-Identifier: Apache-2.0
// SVGF's work skipping (methods/svgf/denoiser.h, filter/work_mask.h). The pixels that need
// denoising (W, the bounding spans of Frame::work) must come out bit-identical to skip=off, so
// every pass computes every pixel a later pass reads for them, planned backwards:
//   à-trous iteration i (step 2^i) reads 5x5 taps 2 * 2^i away and invPhiL at its own pixels
//   (which reads the 3x3 variance of its input, within the taps' reach), so its input must be
//   exact on its computed region dilated by 2 * 2^i; the last iteration computes W;
//   the iteration whose output becomes the colour history (feedbackTap) also computes
//   W dilated by kHistoryMargin, so that next frame's reprojection of a pixel in W (bilinear 2x2
//   taps, SVGF's 3x3 box fallback: 2 pixels) reads exact history when it moves by less than a
//   pixel; a larger move onto a pixel skipped last frame reads that pixel's cheap history (the
//   integrated colour) instead of the filtered one;
//   the variance estimate (7x7 over the integrated colour and moments) computes what iteration 0
//   reads; the temporal integration runs everywhere (the history stays complete).
// With 5 iterations the variance estimate computes W dilated by 62 pixels (2 * (1+2+4+8+16)), the
// last iteration W itself. Pixels outside W put out the integrated colour (the cheap path).
// With TAA (Settings::taa, off by default for this reason) nothing is skipped: the TAA samples its
// history at any on-screen position, not only where the reprojection accepted it (that is what
// smooths a silhouette against the sky), so under camera motion a needed pixel's history reaches
// one pixel further into the skipped ones every frame, and no fixed margin keeps it exact. Making
// skipped sky pixels skip-independent (Falcor leaves environment pixels unfiltered) is the way
// back.
#include "base/parallel.h"
#include "cpu/rgb_rows.h"
#include "methods/svgf/denoiser.h"
#include "methods/svgf/kernels.h"

#include <algorithm>

namespace afn::svgf {

namespace {

constexpr int kHistoryMargin = 2; ///< pixels: bilinear 2x2 + 3x3 box fallback around a pixel

} // namespace

bool Denoiser::planRegions(const Frame& f)
{
    if (!f.hasWorkMask() || m_settings.taa)
        return false;
    m_work = WorkRegion::fromMask(f.work);
    const int n = m_settings.iterations;
    m_passRegions.assign(static_cast<std::size_t>(n), WorkRegion());
    WorkRegion need = m_work; // pixels whose output of the pass being planned must be exact
    for (int i = n - 1; i >= 0; --i) {
        if (i == m_settings.feedbackTap)
            need = need.united(m_work.dilated(kHistoryMargin));
        m_passRegions[i] = need;
        need = need.dilated(2 << i);
    }
    m_varianceRegion = need;
    return true;
}

void Denoiser::copyColor(const Planes& src, int firstPlane, const WorkRegion* region, Image& dst)
{
    const int w = dst.width();
    parallelRows(dst.height(), [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const int x0 = region ? region->x0(y) : 0, x1 = region ? region->x1(y) : w;
            cpu::interleaveRgbRow(src.row(firstPlane, y), src.row(firstPlane + 1, y),
                src.row(firstPlane + 2, y), dst.at(0, y), x0, x1);
        }
    });
}

void Denoiser::copyPlanes(
    const Planes& src, int firstPlane, const WorkRegion* region, Planes& dst, int firstDst)
{
    const int w = dst.width();
    parallelRows(dst.height(), [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const int x0 = region ? region->x0(y) : 0, x1 = region ? region->x1(y) : w;
            for (int k = 0; k < 3; ++k)
                std::copy(src.row(firstPlane + k, y) + x0, src.row(firstPlane + k, y) + x1,
                    dst.row(firstDst + k, y) + x0);
        }
    });
}

} // namespace afn::svgf
