// SPDX-License-Identifier: Apache-2.0
// The AFN network's input tone map, clip(max(x, 0)^(1/2.2), 0, 1) (training/afn/color.py
// tonemap), without libm's powf: it took 12 % of afn's CPU time at 720p (9 calls per pixel:
// both colours of the prediction input and the refinement input).
//
// Method (the same operations in the scalar and the AVX-512 code, so both give the same bits; the
// files are compiled without FMA contraction, see CMakeLists.txt):
//   x <= 0 or NaN -> 0; x >= 1 -> 1; else x = m 2^e with m in [sqrt(1/2), sqrt(2)) (exact) and
//   x^(5/11) = 2^(5 q) * 2^(5 j / 11) * exp(5/11 ln m), e = 11 q + j (j = 0..10, a table),
//   ln m = 2 s (1 + s^2/3 + s^4/5 + s^6/7 + s^8/9), s = (m - 1) / (m + 1) (|s| <= 0.172),
//   exp by its degree-6 Taylor polynomial (|5/11 ln m| <= 0.158), 2^(5 q) exactly (ldexp).
//   Splitting the exponent keeps the relative error small for tiny x too (no large logarithm).
// Against std::pow: within 3e-7 absolute and 4 ulp over (0, 1) (tests/unit/core/methods/afn/
// test_afn_tone_map.cpp sweeps every 97th float of (0, 1), denormals included); the PyTorch
// parity tolerance (4e-6) holds unchanged. NaN gives 0 (std::pow gave NaN; the gather never
// passes NaN on).
#pragma once

namespace afn::afnet {

/// One value (portable).
float toneMap(float x);

/// out[i] = toneMap(in[i]) for i < n (AVX-512F where the CPU has it, else toneMap; the same bits).
/// `in` and `out` may be the same array.
void toneMapRun(const float* in, float* out, int n);

/// The tone map of the inputs of a network that runs in bf16, which rounds them to 8 significant
/// bits (relative step 2^-8) next: on AVX-512, 2^(5/11 log2 x) by two fitted polynomials (log2 of
/// the mantissa, degree 5; 2^f, degree 4) with FMAs, relative error below 1e-5 against toneMap
/// (tests/unit/core/methods/afn/test_afn_tone_map.cpp), about half the instructions and no
/// division; the same limits (x <= 0 or NaN -> 0, x >= 1 -> 1). Elsewhere (and for the tail of a
/// run) toneMap. `in` and `out` may be the same array.
void toneMapRunBf16(const float* in, float* out, int n);

} // namespace afn::afnet
