// SPDX-License-Identifier: Apache-2.0
// Copies between structure-of-arrays planes (svgf's methods/svgf/planes.h, afn's post-filter) and
// packed 3-float pixels (an Image row): plain loops the compiler vectorises in each clone of
// cpu/target.h. Pure copies, so every instruction set gives the same bits.
#pragma once

namespace afn::cpu {

/// dst[3 x + k] = plane k[x] for x in [x0, x1).
void interleaveRgbRow(const float* r, const float* g, const float* b, float* dst, int x0, int x1);
/// plane k[x] = src[3 x + k] for x in [0, w).
void deinterleaveRgbRow(const float* src, float* r, float* g, float* b, int w);

} // namespace afn::cpu
