// SPDX-License-Identifier: Apache-2.0
// Internal to methods/afn/tone_map*.cpp: the constants of the tone map, shared by the scalar and
// the AVX-512 code (methods/afn/tone_map.h describes the method).
#pragma once

namespace afn::afnet::tonemap {

constexpr float kSqrt2 = 1.41421356237309505f;
constexpr float kInvGamma = 5.0f / 11.0f; ///< 1 / 2.2
/// 2^(5 j / 11), j = 0..10 (rounded to float; 16 entries for a vector permute).
constexpr float kPow2Fifths[16]
    = { 1.0f, 1.370350957f, 1.877861857f, 2.573329687f, 3.526365042f, 4.832357883f, 6.622026443f,
          9.074500084f, 12.43525028f, 17.04065704f, 23.35168076f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f };
/// ln m = 2 s (1 + s^2 (c3 + s^2 (c5 + s^2 (c7 + s^2 c9)))), s = (m - 1) / (m + 1).
constexpr float kLogC3 = 1.0f / 3.0f, kLogC5 = 1.0f / 5.0f, kLogC7 = 1.0f / 7.0f,
                kLogC9 = 1.0f / 9.0f;
/// exp(u) = 1 + u (1 + u (e2 + u (e3 + u (e4 + u (e5 + u e6))))), |u| <= 0.158.
constexpr float kExpC2 = 1.0f / 2.0f, kExpC3 = 1.0f / 6.0f, kExpC4 = 1.0f / 24.0f,
                kExpC5 = 1.0f / 120.0f, kExpC6 = 1.0f / 720.0f;

/// toneMapRunBf16: log2(1 + t) ~ sum c_k t^k on [0, 1) (fitted for absolute error: 1.3e-5) and
/// 2^f ~ sum c_k f^k on [-1/2, 1/2] (fitted for relative error: 2.7e-6).
constexpr float kLog2C[6] = { 1.2554382919915952e-05f, 1.4416842460632324f, -0.7079913020133972f,
    0.4136277437210083f, -0.19219395518302917f, 0.04487327113747597f };
constexpr float kExp2C[5] = { 0.9999992847442627f, 0.6931218504905701f, 0.240247443318367f,
    0.05591777339577675f, 0.00957007147371769f };

} // namespace afn::afnet::tonemap
