// SPDX-License-Identifier: Apache-2.0
// Albedo demodulation before filtering and remodulation after it (shared by ta, svgf and bmfr).
//
// Convention (chosen here; the paper follows Chaitanya et al. without giving an epsilon):
//   irradiance = colour / max(albedo, kAlbedoEpsilon)      per channel
//   radiance   = filtered * max(albedo, kAlbedoEpsilon)    per channel
// kAlbedoEpsilon is a power of two (2^-10 ~ 0.001, Falcor's 0.001 rounded), so for zero or tiny
// albedo the division and the multiplication are both exact: such pixels round-trip bit-exactly and
// never blow up. When the colour is already irradiance (Frame::colorDemodulated, BMFR dataset), the
// colour is used as is and remodulated by the plain albedo, exactly as BMFR does (albedo * result).
// Without an albedo input the factor is 1. Irradiance is clamped to [0, kMaxIrradiance] so that
// squares (SVGF moments, BMFR regression) stay finite in float.
#pragma once

#include "filter/frame.h"

#include <cstddef>

namespace afn {

/// Floor of the albedo divisor (2^-10).
constexpr float kAlbedoEpsilon = 1.0f / 1024.0f;
/// Largest irradiance value kept (squares stay below FLT_MAX).
constexpr float kMaxIrradiance = 1e15f;

/// Write the frame's demodulated colour (3 channels, frame size) into `irradiance`, which may be
/// frame.color itself (in place: each value is read before it is written; the Filter base does
/// this, so that a frame holds one colour image).
void demodulate(const Frame& frame, Image& irradiance);

/// Rows [y0, y1) of demodulate(), `irradiance` already of the frame's size (the Filter base runs
/// them row band by row band with the accumulation: the same values, one pass less).
void demodulateRows(const Frame& frame, Image& irradiance, int y0, int y1);

/// The factor remodulate() multiplies channel k of pixel (x, y) by (1 without an albedo).
float albedoFactorAt(const Frame& frame, int x, int y, int k);

/// Write `irradiance` (3 channels) times the frame's albedo factor into `radiance` (3 channels).
/// `radiance` may be the same image as `irradiance`.
void remodulate(const Frame& frame, const Image& irradiance, Image& radiance);

/// Row y of remodulate() written to 3 floats per pixel at `out + x * pixelStride` (bytes), e.g.
/// straight into a caller's buffer (Filter::denoiseDemodulated); the same values as remodulate().
/// `toCaller`: `out` is the caller's output, which nothing in the frame reads again (packed rows
/// are then written with streaming stores on AVX-512).
void remodulateRow(const Frame& frame, const Image& irradiance, int y, std::byte* out,
    std::ptrdiff_t pixelStride, bool toCaller = false);

} // namespace afn
