// SPDX-License-Identifier: Apache-2.0
// Internal to methods/afn/tone_map.cpp: the tone map 16 values at a time (tone_map_avx512.cpp).
#pragma once

namespace afn::afnet {

/// out[i] = toneMap(in[i]) for i < the returned count (the largest multiple of 16 <= n), the
/// scalar operations lane by lane. AVX-512F only (cpu::activeIsa() == Avx512).
int toneMapRunAvx512(const float* in, float* out, int n);

/// The same count of toneMapRunBf16's values (tone_map.h), with FMAs. AVX-512F only.
int toneMapRunAvx512Bf16(const float* in, float* out, int n);

} // namespace afn::afnet
