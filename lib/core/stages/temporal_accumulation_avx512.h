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

} // namespace afn
