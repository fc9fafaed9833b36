// SPDX-License-Identifier: Apache-2.0
// Temporal anti-aliasing of the denoised radiance: the last step of BMFR (official bmfr.cl `taa`)
// and of SVGF (Schied et al. 2017, Fig. 2: remodulation, then TAA), shared by both methods.
//
// Per pixel: the history (the previous output) sampled bilinearly at the reprojected position over
// in-image taps (the reprojection's accept mask is not used: the clamp below is the history test,
// as in bmfr.cl; pixels whose reprojection fell back to SVGF's 3x3 box or left the screen take no
// history), clamped in YCoCg to the average of the 3x3 box and the 5-tap cross min/max boxes of
// the current frame, then blended: max(0, h + alpha (c - h)). History inside the box is kept
// bit-exactly (not converted to YCoCg and back), so a static image is a fixed point. Applied to
// linear radiance (BMFR applies it after its gamma tone map; afn's output stays linear).
//
// Why it matters at 1 spp: a pixel on a silhouette sees one side or the other in each frame (the
// renderer jitters the sample inside the pixel), its reprojection rejects the history when the
// side changes, and SVGF's output keeps the aliased, flickering edge; TAA averages the two.
//
// Implementation: rows of 3 (YCoCg of rows y - 1, y, y + 1, their 3-wide min/max), then the clamp
// and blend of a row in plain loops the compiler vectorises (AFN_CPU_KERNEL_CLONES; the file is
// compiled without FMA contraction, so every clone gives the bits of the per-pixel definition:
// tests/unit/core/stages/test_taa.cpp compares it with a direct per-pixel evaluation).
#pragma once

#include "base/image.h"
#include "stages/history_trust.h"
#include "stages/reproject.h"

namespace afn {

/// Weight of the current frame in the blend (BMFR's 0.2).
constexpr float kTaaAlpha = 0.2f;

/// Pixels around a work region whose TAA inputs must be exact (work skipping): the 3x3 clamp box
/// (1 pixel) and the next frame's bilinear history taps (2 pixels).
constexpr int kTaaWorkMargin = 3;

/// Temporal anti-aliasing of `current` (3 ch radiance) against `history` (the previous output, 3
/// ch) into `out` (resized; may not alias the inputs). Without usable history (first frame, a
/// history of another size, or a reprojection without history) `out` is a copy of `current`.
void temporalAntialias(
    const Reprojector& taps, const Image& current, const Image& history, float alpha, Image& out);

/// TAA with its own history: apply() returns this frame's output, which is kept as the next
/// frame's history.
class TemporalAntialiasing {
public:
    void reset() { m_hasHistory = false; }
    /// TAA of `current` into `spare` (a frame-size image the caller lends, e.g. a scratch image of
    /// its own), which then becomes the history: `spare` gets the previous history's buffer back.
    /// With `trust` (the method's history trust, stages/history_trust.h) the output is pulled
    /// towards `current` where the trust is below 1.
    const Image& apply(const Reprojector& taps, const Image& current, float alpha, Image& spare,
        const HistoryTrust* trust = nullptr);

private:
    Image m_output;
    bool m_hasHistory = false;
};

} // namespace afn
