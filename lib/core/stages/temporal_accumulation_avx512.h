// SPDX-License-Identifier: Apache-2.0
// Internal to stages/temporal_accumulation.cpp: the blend of a static camera's pixels with AVX-512F
// (temporal_accumulation_avx512.cpp).
#pragma once

namespace afn {

/// 16 consecutive pixels whose own previous pixel was accepted (Reprojector::ownPixelAccepted):
/// alpha = max(1 / (s + 1), alphaMin) with s = prevSpp; where the pixel's history trust t is
/// below 1, alpha += (1 - alpha) (1 - t) and s *= t (stages/history_trust.h); acc =
/// blendHistory(prev, c, alpha) per channel, spp = alpha < 1 ? min(s + 1, kMaxHistoryLength) : 1:
/// the scalar operations lane by lane (the same bits). `c`, `prev` and `acc` are 48 packed floats,
/// `prevSpp`, `trust` and `spp` 16; `trust` nullptr is trust 1. AVX-512F only (cpu::activeIsa()
/// == Avx512).
void blendOwnHistory16(const float* c, const float* prev, const float* prevSpp, float alphaMin,
    const float* trust, float* acc, float* spp);

/// The history trust's sums (stages/history_trust.h) of 16 consecutive pixels whose own previous
/// pixel was accepted, two whole blocks: into sums[0 .. 2 kSums) (block x / 8 and the next, both
/// 0 before) the count 8 and, per channel, the sums of c, of h and of (c - h)^2, each summed pixel
/// by pixel from the left as HistoryTrust::RowAdder sums (the same bits). `c` and `h` are 48
/// packed floats; nothing is written where `sums` is nullptr. AVX-512F only.
void addOwnHistoryTrust16(const float* c, const float* h, float* sums);

} // namespace afn
