// SPDX-License-Identifier: Apache-2.0
// The row kernel of the temporal anti-aliasing (stages/taa.h): the clamp and blend of one row, in
// a portable version (stages/taa.cpp, the per-pixel definition's operations) and an AVX-512 one
// (stages/taa_avx512.cpp, the same operations 16 pixels at a time, the same bits; used where
// cpu::activeIsa() is Avx512). Included by those two files and their test only.
#pragma once

namespace afn {

/// One row of the ring: YCoCg planes and their min/max over the pixel and its two neighbours
/// (columns clamped to the image).
struct TaaRingRow {
    float* v[3];
    float* lo[3];
    float* hi[3];
};

/// The inputs of one row: the bounds from the rows above, at and below (box: their 3-wide
/// min/max; cross: the centre row's 3-wide min/max and the values above and below), the current
/// and history planes, planes out.
struct TaaBlendRow {
    const TaaRingRow* above;
    const TaaRingRow* centre;
    const TaaRingRow* below;
    const float* cur[3]; ///< current radiance planes
    const float* hist[3]; ///< history planes
    const float* has; ///< 1 where the pixel has history, else 0
    float alpha;
    float* out[3]; ///< output planes
};

/// Per pixel x < w: history clamped in YCoCg to the average of the box and cross bounds (kept
/// as it is when inside), blended max(0, h + alpha (c - h)) (|v| < FLT_MIN -> 0); c where the
/// pixel has no history.
void blendRowPortable(const TaaBlendRow& r, int w);
void blendRowAvx512(const TaaBlendRow& r, int w);

} // namespace afn
