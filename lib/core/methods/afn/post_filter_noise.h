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

#include <vector>

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

/// `scale` = scale_p above for every pixel of a w x h frame, `sigmaLuminance` being the filter's
/// sigma_l; `meanPlane` and `squarePlane` are scratch. Each of the three holds w * h floats.
void postFilterLuminanceScale(const PostFilterNoiseInputs& in, int w, int h, float sigmaLuminance,
    float* meanPlane, float* squarePlane, float* scale);

} // namespace afn::afnet
