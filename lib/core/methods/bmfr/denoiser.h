// SPDX-License-Identifier: Apache-2.0
// Blockwise multi-order feature regression (Koskela et al., TOG 2019; official OpenCL bmfr.cl).
// Per frame, on demodulated irradiance:
//   1. BMFR temporal accumulation (the shared stage, stages/temporal_accumulation.h);
//   2. regression of the accumulated colour in square blocks (regression.cpp): features
//      1, n.xyz, p.xyz, p.xyz^2 (no cross terms); without positions the screen coordinates (and the
//      depth when present) take the place of p; without normals those are dropped. The block grid
//      shifts every frame by one of 16 offsets; one Householder QR per block fits all channels;
//   2b. detail the fit cannot express, kept where it stands above the accumulation's noise
//      (detail.h; not in the paper: the fit alone falls below the noisy input from 16 spp on);
//   3. second accumulation of the regression output with the same taps and
//      alpha = max(1/len, secondAlphaMin) (len = TA history length after this frame);
//   4. remodulation by albedo, then TAA (stages/taa.h) on the linear radiance.
// Work skipping (Frame::work): only the blocks that hold a pixel of the work region dilated by
// kWorkMargin are fitted; the others pass the accumulated colour on (the cheap path) through the
// second accumulation and TAA, which run everywhere (per pixel, cheap). The margin covers TAA's
// 3x3 clamp box (1 pixel) and the history taps of the next frame (bilinear + 1: 2 pixels), so a
// pixel that needs denoising is bit-identical to skip=off while it moves by less than a pixel per
// frame relative to the mask (always with a static camera and mask).
#pragma once

#include "filter/work_region.h"
#include "stages/highlight_bypass.h"
#include "stages/taa.h"
#include "stages/temporal_accumulation.h"

namespace afn::bmfr {

/// BMFR parameters (official values as defaults; ranges and help in settingsBinding()). The
/// first accumulation's alphaMin is the shared stage's (AccumulationSettings).
struct Settings {
    float secondAlphaMin = 0.1f; ///< second accumulation minimum (SECOND_BLEND_ALPHA 0.1)
    int blockSize = 32; ///< block edge in pixels (BMFR supports only 32)
    float noise = 0.01f; ///< uniform feature noise amplitude (NOISE_AMOUNT 1e-2)
    enum class Detail { Auto, Off, On };
    Detail detail = Detail::Auto; ///< keep the detail above the noise after the fit (detail.h)
    int spp = 0; ///< the shared "spp" parameter (detail=auto: on from kDetailSpp)
    bool taa = true; ///< apply the final TAA step
    float taaAlpha = kTaaAlpha; ///< TAA weight of the current frame (BMFR 0.2)
    /// Factor of the highlight bypass's limit over the frame's bright level, 0 = off
    /// (stages/highlight_bypass.h; not in BMFR): the regression fits the accumulated colour
    /// clamped, the excess is added back to the fit at its own pixel.
    float highlights = kHighlightFactor;
};

/// detail=auto keeps detail from this many samples per pixel: below, the one-frame noise estimate
/// is too noisy itself (at 1 spp the restored residual flickers: +0.3 dB, temporal error +20 %).
constexpr int kDetailSpp = 4;

/// The descriptors of Settings (the method's own parameters).
const ParamBinding<Settings>& settingsBinding();

/// Fit the blockwise regression of `noisy` (3 ch, demodulated) over the frame's features and write
/// the per-pixel fitted values (>= 0) into `filtered`. `blockFrame` selects the block offset.
/// With a `region` (work skipping), blocks that hold none of its pixels are not fitted: their
/// pixels get `noisy` as it is.
void regression(const Frame& f, const Image& noisy, const Settings& s, int blockFrame,
    Image& filtered, const WorkRegion* region = nullptr);

/// Pixels around the work region whose regression must be exact (see the file comment).
constexpr int kWorkMargin = kTaaWorkMargin;

class Denoiser {
public:
    void setSettings(const Settings& s) { m_settings = s; }
    void reset();
    /// Denoise frame `f` into remodulated radiance (3 ch, returned; valid until the next call and
    /// while `scratch` is unchanged), from the shared stages' results: the taps of this frame and
    /// the temporal accumulation of its demodulated colour. `scratch` is a frame-size image the
    /// caller lends for this frame (TemporalAccumulator::scratch()).
    /// `irradiance`: the frame's demodulated colour (f.color's buffer, not read after this call),
    /// rewritten as scratch.
    const Image& process(const Frame& f, const Reprojector& taps, const TemporalAccumulator& ta,
        Image& scratch, Image& irradiance);

    /// Pixels of the last frame whose highlight bypassed the filter (stages/highlight_bypass.h).
    std::int64_t highlightPixels() const { return m_highlights.pixels(); }

private:
    Settings m_settings;
    bool m_hasHistory = false;
    /// Histories: m_filtered (second accumulation), m_taa (the last output); scratch: m_spare
    /// and the caller's (regression, then the remodulated radiance; pipeline.cpp).
    Image m_filtered, m_spare;
    TemporalAntialiasing m_taa;
    HighlightBypass m_highlights; ///< this frame's
};

} // namespace afn::bmfr
