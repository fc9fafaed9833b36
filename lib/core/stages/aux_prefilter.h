// SPDX-License-Identifier: Apache-2.0
// Possibly-noisy auxiliary buffers: the shared stage that makes demodulation, edge-stopping and
// network features safe when albedo, normals or depth are noisy.
//
// The problem. Methods divide the colour by the albedo, filter, and multiply by the albedo again
// (stages/demodulate.h). When the albedo is itself 1-spp noise (Blender's Denoising Albedo on
// metal and glass, any AOV under depth of field or motion blur), the remodulation multiplies the
// clean filtered irradiance by that noise and the output gets the speckle back, whatever the
// filter. Noisy normals and depth make edge-stopping weights random (SVGF), feed noise into
// regression features (BMFR) and network inputs (AFN), and reject history (reprojection).
//
// The choice. Demodulation and remodulation use the SAME per-pixel factor d, so any factor is
// unbiased (colour / d * d = colour): the factor only decides in which domain the filter works.
// A per-pixel factor is worth having where it is reliable (it takes texture out of the signal);
// where it is noise it should be smooth. So, in "noisy" mode:
//   1. flags    speckle pixels of each buffer (stages/aux_noise.h: differs from all 8 neighbours);
//   2. u        share of flagged pixels in the 5x5 window, or, where more is the denser speckle
//               of the 5x5 window's differing adjacent pairs (stages/aux_noise.h
//               discontinuityShares; ramped from kAuxDenseLow to kAuxDenseHigh onto the same
//               0..kAuxUnreliableShare scale), accumulated over time through the
//               reprojection (the "variance over neighbourhood and history");
//   3. r        reliability = clamp(1 - u / kAuxUnreliableShare, 0, 1): 1 on clean surfaces
//               (flag-free windows), 0 where 4 or more of 25 neighbours are speckle;
//   4. albedo   d = r * albedo + (1 - r) * h, h = temporal accumulation (alpha >= 0.1, same taps
//               and history rule as the colour's) of the 5x5 mean albedo: a smooth, stable
//               estimate of the expected albedo. Where r = 0 the demodulation divides by a smooth
//               field, i.e. the method effectively filters the colour without per-pixel
//               demodulation (a smooth gain commutes with the filter up to its own variation);
//               where the unreliable factor is also near zero, d >= (1 - r) / 32, which bounds
//               the gain at 32x instead of 1024x (stages/demodulate.h's 2^-10 floor).
//               A pixel flagged itself takes r = 0 whatever its window's share: otherwise an
//               isolated outlier in an otherwise clean window (a black albedo sample on a
//               coated surface, 1-3 of 25 pixels) keeps its value and comes back from every
//               method as a dark or bright dot (docs/afn-evaluation.md).
//   5. normal   n' = normalize(r n + (1 - r) mean5x5(n)),
//      depth    z' = r z + (1 - r) mean5x5(z) over pixels with a surface,
//               before reprojection, so history acceptance, SVGF's edge-stopping, BMFR's features
//               and AFN's inputs all see the prefiltered geometry.
// The rewritten buffers replace the frame's (Frame::albedo, normal, depth): every method, the
// remodulation and the AFN features (hence training, through afntool --features) see the same
// values. Flags and r are per buffer; a clean buffer in a noisy frame is left as it is (r = 1).
//
// "clean" leaves every buffer untouched (bit-identical to not running this stage);
// "auto" (default) decides on the first frame of each history: noisy when the albedo's or the
// normal's speckle share exceeds kAuxNoisyShare (0.5 %) and the colour's sample count ("spp",
// 0 = unknown) is below kAuxTrustedSpp, clean otherwise. The speckle test cannot tell noise from
// texture at the pixel scale (a fine texture, or one refracted through glass, differs from its 8
// neighbours too), and the auxiliary buffers' own sampling noise falls with the sample count: on
// the afn-v2 renders the 16-spp albedo flags as much "speckle" as the 1-spp one (2-9 % on the
// atrium scenes), and there prefiltering it cost svgf, bmfr and afn 0.6-1.7 dB on average
// (docs/afn-evaluation.md). There, where speckle is found, the albedo keeps its
// given values except for its grain: the sub-pixel texture sampling noise a 16-spp albedo still
// has, which remodulation would put back as a faint grain, is averaged over time within
// kAuxGrainLimit of each given value (limitGrain; stats.auxGrainLimited). The decision holds
// until the history is reset, so a sequence is filtered in one mode (a changed "aux" parameter,
// too, takes effect at the next reset: afnResetFilter or a new filter). With colour that is already
// demodulated (AFN_CONVENTION_COLOR_DEMODULATED) the albedo is never changed (the colour was
// divided by the given albedo; only that one remodulates it exactly).
#pragma once

#include "base/params.h"
#include "filter/frame.h"
#include "stages/aux_noise.h"
#include "stages/reproject.h"

namespace afn {

/// The "aux" parameter of every method that demodulates.
struct AuxSettings {
    enum class Mode { Auto, Clean, Noisy };
    Mode aux = Mode::Auto; ///< auto: decided from the data on the first frame of a history
    /// Samples per pixel of the colour input, 0 = unknown (the host reads it from the file:
    /// afntool, Blender's cycles.<layer>.samples). Shared with the afn method, which picks its
    /// model by it (methods/afn/model_set.h).
    int spp = 0;
};

/// From this sample count on, aux=auto uses the auxiliary buffers as given, the albedo's grain
/// limited over time (see the file comment).
constexpr int kAuxTrustedSpp = AFN_AUX_TRUSTED_SPP; // 16 (afn/afn.h)
/// Largest relative change the grain limit makes to a given albedo value (AuxPrefilter::
/// limitGrain): 10 %, the speckle test's albedo threshold (aux_noise.h).
constexpr float kAuxGrainLimit = 0.1f;

/// Descriptors of AuxSettings (in the table of every method that demodulates).
const ParamBinding<AuxSettings>& auxBinding();

/// Share of speckle pixels in a 5x5 window at which a buffer is fully unreliable (4 of 25).
constexpr float kAuxUnreliableShare = 0.16f;
/// The 5x5 mean of discontinuityShares (stages/aux_noise.h) from which a buffer counts as dense
/// speckle (its reliability falls from 1 at kAuxDenseLow to 0 at kAuxDenseHigh). A checker of
/// 4-pixel squares gives 0.2-0.3 depending on the window's phase, stripes two pixels wide 0.25:
/// left as they are; speckle of density 30 % gives about 0.42, 40-50 % about 0.48-0.5.
constexpr float kAuxDenseLow = 0.3f;
constexpr float kAuxDenseHigh = 0.45f;
/// Minimum blend factor of the albedo's temporal accumulation.
constexpr float kAuxAlbedoAlphaMin = 0.1f;
/// Floor of the demodulation factor where it is unreliable (2^-5; scaled by 1 - r).
constexpr float kAuxNoisyAlbedoFloor = 1.0f / 32.0f;

/// What the stage measured and decided for the last frame (afnGetFilterFloat "stats.aux*").
struct AuxReport {
    bool noisy = false; ///< prefiltering in effect for this frame's history
    bool grainLimited = false; ///< from kAuxTrustedSpp: the albedo's grain limited over time
    double albedoSpeckle = -1.0; ///< share of speckle pixels, -1 without the input
    double normalSpeckle = -1.0;
    double depthSpeckle = -1.0;
};

class AuxPrefilter {
public:
    void setSettings(const AuxSettings& s) { m_settings = s; }
    /// Drop the history and the auto decision (next frame decides again).
    void reset();

    /// Before reprojection: measure, decide (first frame of a history), prefilter normal and
    /// depth of `frame` in place.
    void prepare(Frame& frame);
    /// After reprojection (`taps` null when the method does not reproject): replace the frame's
    /// albedo by the demodulation factor d (see the file comment).
    void finish(Frame& frame, const Reprojector* taps);

    const AuxReport& report() const { return m_report; }
    /// True when the last frame's speckle shares are not measured yet: a history decided clean
    /// (neither prefiltered nor grain-limited) reads no flags, so its shares, which are only
    /// reported, are measured when asked for (measureShares), not on every frame.
    bool sharesPending() const { return m_sharesPending; }
    /// Measure the pending shares on the last frame's albedo, normal and depth as given (empty
    /// views for absent inputs); the same counts prepare() would have made. No effect when none
    /// is pending.
    void measureShares(
        const ImageView& albedo, const ImageView& normal, const ImageView& depth) const;

private:
    void limitGrain(Frame& frame, const Reprojector* taps);

    AuxSettings m_settings;
    mutable AuxReport m_report; ///< shares measured late by measureShares()
    mutable bool m_sharesPending = false;
    bool m_decided = false;
    bool m_hasHistory = false;
    Image m_albedoFlags, m_normalFlags, m_depthFlags; ///< speckle flags (kept in noisy mode)
    Image m_share, m_mean, m_tmp, m_depthValid;
    Image m_edges, m_dense; ///< discontinuity shares and their 5x5 mean (albedo, normal)
    Image m_hist, m_prevHist; ///< per pixel: smoothed albedo (3), flag share (1), length (1)
};

} // namespace afn
