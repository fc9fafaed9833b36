// SPDX-License-Identifier: Apache-2.0
// Internal to methods/svgf/temporal.cpp: SVGF's temporal integration of a static camera's pixels
// with AVX-512F (integrate_avx512.cpp).
#pragma once

namespace afn::svgf {

/// 16 consecutive pixels whose own previous pixel was accepted (Reprojector::ownPixelAccepted),
/// the scalar operations of Denoiser::integrate lane by lane (the same bits): l = luminance(c),
/// len = min(prevLength + 1, 255), alpha = max(alpha, 1 / len) and momentsAlpha likewise, colour
/// and moments (l, l^2) blended with blendHistory (stages/reproject.h), length = len, and the
/// luminance of the blended colour; where the history trust t (16 floats; nullptr: 1) is below 1,
/// both alphas are raised by (1 - alpha) (1 - t) and len = min(ceil(prevLength t) + 1, 255). `c`
/// is 48 packed floats (RGB); `prev` the previous frame's colour, moment 1, moment 2 and length (6
/// pointers to 16 floats); `out` the same 6 and the luminance (7 pointers). AVX-512F only
/// (cpu::activeIsa() == Avx512).
void integrateOwnHistory16(const float* c, const float* const* prev, float alpha,
    float momentsAlpha, const float* trust, float* const* out);

/// The history trust's sums (stages/history_trust.h) of 16 consecutive pixels whose own previous
/// pixel was accepted, two whole blocks, as temporal.cpp's addToTrust adds them pixel by pixel
/// (the same bits): the history colour scaled by s = m1 / luminance (1 where the luminance is not
/// above 0), then stages/temporal_accumulation_avx512.h's addOwnHistoryTrust16. `c` is 48 packed
/// floats (RGB); `prev` the previous frame's colour and moment 1 (4 pointers to 16 floats);
/// nothing is written where `sums` is nullptr. AVX-512F only (cpu::activeIsa() == Avx512).
void addOwnTrust16(const float* c, const float* const* prev, float* sums);

} // namespace afn::svgf
