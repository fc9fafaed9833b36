// SPDX-License-Identifier: Apache-2.0
// Noise estimate of an auxiliary buffer (albedo, normal, depth): how much of it is 1-spp speckle.
//
// Renderers' denoising AOVs are not always first-hit quantities: Blender's Denoising Albedo and
// Denoising Normal (Arnold's denoise_albedo, RenderMan's albedo) follow specular and refractive
// bounces to the next diffuse hit, and every AOV is sampled with the pixel's depth-of-field and
// motion-blur samples. At 1 spp such a buffer is as noisy as the beauty on metal, glass, defocused
// and moving objects. The estimate used here is the share of "speckle" pixels:
//
//   D(p)      = min over the 8 neighbours q of p (inside the image) of dist(p, q)
//   speckle p = D(p) > threshold   (the pixel differs from every neighbour)
//
// A clean buffer is piecewise smooth even at 1 spp: a pixel on an edge, on a texture boundary or on
// a one-pixel-wide wire still agrees with the neighbours on its own side, so D is ~0 almost
// everywhere; a buffer that follows random bounces makes most pixels of the affected surfaces
// disagree with all of their neighbours. Distances (thresholds in AuxNoiseThresholds):
//   albedo  max over channels |a_p - a_q| / max(a_p, a_q, 0.1 over channels)   (relative: the
//           rough gold of examples/sequence varies by tens of percent around a dark level)
//   normal  |n_p - n_q| (Euclidean, unit normals)
//   depth   |z_p - z_q| / min(|z_p|, |z_q|) (relative); pixels without a surface (|z| >= 1e9, the
//           sky) are never speckle and never a neighbour
// The same flags drive the per-pixel reliability of stages/aux_prefilter.h, and afntool --info
// reports the share per role (afnEstimateAuxNoise), so the number a user sees is the one the
// "auto" decision uses.
#pragma once

#include "base/image.h"

#include <cstdint>

namespace afn {

/// Which auxiliary buffer a speckle test reads (selects the distance and the threshold).
enum class AuxKind { Albedo, Normal, Depth };

/// Speckle thresholds per kind (units of the distance above).
struct AuxNoiseThresholds {
    static constexpr float albedo = 0.1f; ///< relative difference (10 %)
    static constexpr float normal = 0.3f; ///< chord length of unit normals (~17 degrees)
    static constexpr float depth = 0.05f; ///< relative depth difference
};

/// Floor of the albedo level that scales albedo differences (dark albedo: absolute 0.01).
constexpr float kAuxAlbedoLevelFloor = 0.1f;

/// The number of speckle pixels of `image` (speckleFlags without writing the flags).
std::int64_t speckleCount(const ImageView& image, AuxKind kind);

/// Share of speckle pixels above which a buffer counts as noisy ("auto" decides on it): 0.5 %.
/// Measured (Blender 3.4, 1 spp, Denoising Albedo): 0.09-0.15 % on scenes without metal or glass
/// (neon, flyby of training/scenes), 1.9-5.0 % with them (examples/sequence, the afn-v2 eval
/// scenes): the threshold sits between with a margin of 3x either way.
constexpr double kAuxNoisyShare = 0.005;

/// Depths at or beyond this are "no surface" (Blender writes 1e10 for the sky).
constexpr float kAuxDepthSky = 1e9f;

/// Write the speckle flags of `image` (1 channel, 0 or 1) into `flags`; returns their count.
/// `image` holds 3 channels (albedo, normal) or 1 (depth); an empty image gives no flags.
std::int64_t speckleFlags(const ImageView& image, AuxKind kind, Image& flags);

/// The number of speckle pixels of `image` (speckleFlags without writing the flags).
std::int64_t speckleCount(const ImageView& image, AuxKind kind);

/// Share of speckle pixels of `image` in [0, 1] (0 for an empty image).
double speckleShare(const ImageView& image, AuxKind kind);

/// Dense speckle, which the test above misses (neighbouring speckles hide each other: Blender's
/// Denoising Albedo on a coated floor at 1 spp is a two-level pattern over 30-50 % of the pixels,
/// where most pixels have a neighbour of the same level). Per pixel, the share of its 4 edge
/// neighbours (inside the image) farther than the kind's threshold, into `out` (1 channel, in
/// [0, 1]); albedo and normal only. Averaged over a 5x5 window (stages/aux_prefilter.h) it is the
/// share of differing adjacent pairs: about 2 p (1 - p) for speckle of density p (0.42-0.5 at
/// 30-50 %), 0.1 across a straight edge, 0.2-0.3 on a checker of 4-pixel squares, 0.25 on stripes
/// two pixels wide, 0.5 on one-pixel stripes (texture that fine is not told from noise at one
/// pixel's scale).
void discontinuityShares(const ImageView& image, AuxKind kind, Image& out);

} // namespace afn
