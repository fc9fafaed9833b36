// SPDX-License-Identifier: Apache-2.0
// Internal to stages/demodulate.cpp: demodulation and remodulation of packed runs of floats with
// AVX-512F (demodulate_avx512.cpp), the scalar operations value by value (the same bits).
#pragma once

namespace afn {

/// o[i] = clampIrradiance(c[i] / max(a[i], kAlbedoEpsilon)), or clampIrradiance(c[i]) when `a` is
/// null; `o` may be `c`. AVX-512F only (cpu::activeIsa() == Avx512).
void demodulateRunAvx512(const float* c, const float* a, float* o, int n);

/// o[i] = clampIrradiance(v[i]) * (plain ? a[i] : max(a[i], kAlbedoEpsilon)). AVX-512F only.
/// `stream`: the run goes to a buffer nothing reads soon (the caller's output): its aligned whole
/// vectors are written with streaming stores (the same values).
void remodulateRunAvx512(
    const float* v, const float* a, float* o, int n, bool plain, bool stream = false);

} // namespace afn
