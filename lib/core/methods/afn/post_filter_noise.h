// SPDX-License-Identifier: Apache-2.0
// How strongly afn's post-filter (post_filter.h) smooths each pixel: its luminance term's scale,
// from an estimate of the noise left in afn's estimate there. Not in the AFN paper; the idea is
// SVGF's variance-guided luminance weight (Schied et al. 2017, Sec. 4.2-4.3), with a cheaper
// estimate chosen for afn:
//
//   m_p, v_p  mean and variance of the luminance (Rec. 709) of the frame's 1-spp irradiance (the
//             demodulated colour the network reads) over the 5x5 box around p (taps clamped to
//             the border): the per-sample noise there, texture taken out by the demodulation
//   n_p       the samples behind p's accumulated colour: min(history length, (2 - a) / a), a the
//             accumulation's minimum blend (alphaMin, 0.2 by default: n <= 9; stages/
//             temporal_accumulation.h: an exponential average with blend a keeps the variance of
//             (2 - a) / a samples however long the history)
//   r_p       = sqrt(v_p / n_p) / (m_p + 1e-3): the relative noise of p's accumulated estimate
//   scale_p   = (sigma_l / 2) clamp(r_p / kPostFilterNoiseReference, 1 / kPostFilterNoiseClamp,
//             kPostFilterNoiseClamp), used by the filter as dl = |l_p - l_q| / (scale_p (l_p +
//             l_q) + 1e-3)
//
// So a dark, noisy corner or a pixel just disoccluded is smoothed more, a clean bright surface or
// one with a long history less (with a constant sigma_l the filter over-smoothed the one and left
// blotches in the other). The constants were chosen on rendered training sequences only (14 of
// them; docs/afn-evaluation.md), the held-out set run once afterwards.
// Without an irradiance guide (or one of another size) every pixel gets sigma_l / 2, one
// constant scale; without a history length n_p = 1 (a single frame).
#pragma once

#include "base/image.h"

#include <cstddef>

namespace afn::afnet {

/// r at which a pixel gets the filter's base sigma_l (kPostFilterSigmaLuminance).
constexpr float kPostFilterNoiseReference = 0.85f;
/// The scale stays within [1 / clamp, clamp] times the base.
constexpr float kPostFilterNoiseClamp = 4.0f;
/// Radius of the box the noise is measured over (5x5).
constexpr int kPostFilterNoiseRadius = 2;

/// What the noise estimate reads; null, empty or mismatched images count as absent.
struct PostFilterNoiseInputs {
    const Image* irradiance = nullptr; ///< 3 ch, the frame's 1-spp demodulated colour
    const Image* historyLength = nullptr; ///< 1 ch, samples accumulated (1 = no history)
    float maxSamples = 9.0f; ///< (2 - alphaMin) / alphaMin of the accumulation
};

/// scale_p above, row by row: a band of the post-filter's rows asks for its rows in increasing
/// order from any first row; the box means along x of the 2 r + 1 rows around the last one are
/// kept in a ring. post_filter_noise.cpp.
class PostFilterNoiseRows {
public:
    /// Floats of storage the rows of a frame of width w need.
    static std::size_t storageFloats(int w);

    /// For a w x h frame, `sigmaLuminance` being the filter's sigma_l; `storage` holds
    /// storageFloats(w) floats, used until the last row.
    PostFilterNoiseRows(
        const PostFilterNoiseInputs& in, int w, int h, float sigmaLuminance, float* storage);

    /// Row y's scale into `scale` (w floats); y at least the previous call's.
    void row(int y, float* scale);

private:
    /// Box row y's means of l and l^2 (its slot of the ring).
    float* boxMean(int y) const;
    float* boxSquare(int y) const;

    const Image* m_irradiance;
    const Image* m_history;
    int m_w, m_h;
    float m_maxSamples, m_base;
    float* m_storage;
    int m_nextBox = -1; ///< the next box row to compute (-1: none yet)
};

} // namespace afn::afnet
