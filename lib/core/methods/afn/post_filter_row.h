// SPDX-License-Identifier: Apache-2.0
// One output row of one half-pass of afn's edge-aware post-filter (post_filter.h: the formula),
// the kernel post_filter.cpp runs the six half-passes with. Internal to the post-filter.
#pragma once

#include "methods/afn/post_filter.h"

#include <cstddef>

namespace afn::afnet {

/// One tap of a half-pass: its offset, spline weight and ring (the depth term's distance in
/// steps).
struct PostFilterTap {
    int dx, dy;
    float h;
    int ring; ///< 1 or 2
};

/// The outer taps of a half-pass (j = -2, -1, 1, 2; the centre tap is the kernel's own).
constexpr int kPostFilterTaps = 4;

/// The 4 outer taps of one 1-D half of the a-trous pass of `step`: along x (horizontal) or y.
void postFilterTaps(bool horizontal, int step, PostFilterTap (&taps)[kPostFilterTaps]);

/// One output row of a half-pass: the colour rows it reads (three planes each; a horizontal
/// half's taps read the pixel's own row), the guide planes' rows (offsets into the frame's
/// planes, the taps' rows clamped to the image) and where it writes: three planes, or the output
/// image's row interleaved (the last half-pass).
struct PostFilterRow {
    const float* centre[3];
    const float* tap[kPostFilterTaps][3];
    std::size_t guideCentre;
    std::size_t guideTap[kPostFilterTaps];
    float* out[3];
    float* interleaved;
};

/// The w pixels of `row` filtered with `taps` (of the pass of `step`) and written out.
void filterPostFilterRow(const PostFilterRow& row, const PostFilterGuidePlanes& g, int w,
    const PostFilterTap* taps, int step);

} // namespace afn::afnet
