// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (postFilter=auto|off|on, settings.h): an a-trous smoothing of the
// final radiance (after the remodulation and the TAA), guided by the frame's albedo, normal and
// depth, to take out the low-frequency blotches the network leaves on flat surfaces. Not in the
// AFN paper; the weights are SVGF's kind (Schied et al. 2017, Sec. 4.3), chosen for afn's output:
//
//   kPostFilterIterations passes of the B3-spline a-trous kernel (h = 1/16, 1/4, 3/8, 1/4, 1/16)
//   at steps 1, 2, 4 (footprint 29 x 29 pixels), each pass separable: a horizontal half (taps
//   q = p + (j step, 0), j = -2..2), normalised, then a vertical half (q = p + (0, j step)) on its
//   result, normalised, each tap q of pixel p weighted by
//     h_j * wn * exp(-(dz + dl + da)) with
//     wn = max(0, n_p . n_q / (|n_p| |n_q|))^64           (1 where either normal is ~0 or absent)
//     dz = |z_p - z_q| / (0.02 max(z_p, 1e-3) step max(|j|, 1) + 1e-6)  (relative depth)
//     dl = |l_p - l_q| / (s_p max(l_p + l_q, 0) + 1e-3)  (relative luminance of the pass's
//          half's input, Rec. 709 weights; s_p the pixel's scale from the noise left in afn's
//          estimate there, post_filter_noise.h: kPostFilterSigmaLuminance / 2 where that noise is
//          typical)
//     da = (|dA_r| + |dA_g| + |dA_b|) / 0.1                (albedo: keeps texture edges)
//   taps outside the image clamped to the border. The centre tap's weight is h_2 = 3/8 > 0, so
//   the normalisation never divides by zero. A tap whose exp(-(dz + dl + da)) is below e^-40, or
//   whose normals' cosine is below 0.3 (both valid), weighs 0: at most 3e-17 of the centre tap's
//   weight, and it keeps denormal floats (about a hundred times slower) out of the sums.
// Radiance, not irradiance, is filtered: dividing by a 1-spp albedo (noisy on glass, in depth of
// field) and multiplying back adds that albedo's noise; the albedo term keeps textures instead.
//
// The parameters (3 passes, sigma_l 0.25, the depth, normal and albedo scales; the noise scale's
// constants) were chosen on the rendered training sequences only; the held-out set was then run
// once (docs/afn-evaluation.md, post-filter). Choice: the separable halves (10 taps a pass
// instead of the 5x5 kernel's 25, whose edge stops a separable pass approximates: a tap reaches a
// diagonal neighbour through the row between) cost 2.5 times fewer weights for the same
// footprint and spline; on afn-v4's 77 training sequences at 1 spp they scored 0.008 dB below the
// 5x5 kernel (27.324 against 27.332 dB, SSIM -0.0004); the held-out set: docs/afn-evaluation.md.
// The guides are the frame's as the shared stages leave them (the aux prefilter's). exp is a
// polynomial approximation (relative error < 3e-6) so the rows vectorise.
#pragma once

#include "base/image.h"
#include "methods/afn/post_filter_noise.h"

#include <vector>

namespace afn::afnet {

constexpr int kPostFilterIterations = 3;
/// Pixels a filtered pixel reads around it: 2 * (1 + 2 + 4).
constexpr int kPostFilterRadius = 28 / 2;
constexpr float kPostFilterSigmaLuminance = 0.25f;

/// The guides of one frame; albedo and normal 3 ch, depth 1 ch, of the radiance's size. A null or
/// empty guide, or one of another size or channel count, is left out (its term is 0). `noise`
/// sets the luminance term's per-pixel scale (post_filter_noise.h); without its irradiance every
/// pixel gets kPostFilterSigmaLuminance.
struct PostFilterGuides {
    const Image* albedo = nullptr;
    const Image* normal = nullptr;
    const Image* depth = nullptr;
    PostFilterNoiseInputs noise;
};

/// The guides as planes, sanitised: albedo (non-finite -> 0; absent: 0), unit normals and their
/// validity (1 where the normal is finite and |n|^2 > 0.5; absent: 0), depth (non-finite -> 1e30,
/// a far background; absent: 1). Absent guides so give their terms 0. `ls` is the luminance
/// term's scale per pixel (post_filter_noise.h). Rows of a band's rings (post_filter.cpp): a
/// row's values start at the same offset in every plane.
struct PostFilterGuidePlanes {
    float *a0 = nullptr, *a1 = nullptr, *a2 = nullptr, *n0 = nullptr, *n1 = nullptr, *n2 = nullptr,
          *nv = nullptr, *z = nullptr, *ls = nullptr;
};

/// Row y of the guides (a w x h frame) written `offset` floats into each of `planes` as
/// PostFilterGuidePlanes describes, except `ls` (post_filter_noise.h). post_filter_guides.cpp.
void buildPostFilterGuideRow(const PostFilterGuides& guides, int w, int h, int y,
    const PostFilterGuidePlanes& planes, std::size_t offset);

/// The filter's storage: each band of the frame's rows (one per thread) keeps rings of the rows
/// its passes and guides are at (a few dozen rows of the width each), kept by the caller from
/// frame to frame so that a sequence allocates them once. Their contents between calls mean
/// nothing.
struct PostFilterWorkspace {
    /// A band's rows are w + kPostFilterPlaneStagger floats apart: rows whose size is a multiple
    /// of 4 KiB would otherwise start at the same offset within a page and share the processor's
    /// L1 cache sets, which the 5 rows of a vertical pass's taps (x 12 planes) overflow.
    std::vector<float> storage;
};

/// Floats between one row's end and the next one's start in a band's rings (one cache line).
constexpr int kPostFilterPlaneStagger = 16;

/// The edge-aware post-filter of `radiance` (3 ch) into `out` (resized) with `workspace`'s
/// rows. `out` may not alias `radiance`. Non-finite guide values count as absent (normal), far
/// (depth) or 0 (albedo). The radiance is taken as finite (afn's inputs are sanitised before the
/// network, gather.cpp); negative radiance counts as luminance 0 in dl.
void edgeAwarePostFilter(const Image& radiance, const PostFilterGuides& guides,
    PostFilterWorkspace& workspace, Image& out);

} // namespace afn::afnet
