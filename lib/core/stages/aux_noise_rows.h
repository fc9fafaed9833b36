// SPDX-License-Identifier: Apache-2.0
// Internal to stages/aux_noise.cpp: the AVX-512 pre-test of the speckle estimate
// (aux_noise_avx512.cpp).
#pragma once

#include "stages/aux_noise.h"

#include <cstdint>

namespace afn {

/// Bit l set when pixel l of the 16 packed RGB pixels at `p` (48 floats; the 3 floats before `p`
/// are pixel -1) is within `t` of its left neighbour under the distance of `kind` (Albedo or
/// Normal, stages/aux_noise.h). AVX-512F only (cpu::activeIsa() == Avx512).
std::uint32_t leftNeighbourWithin16(const float* p, AuxKind kind, float t);

/// Bit l set when pixel l of the 16 depths at `p` (p[-1] is pixel -1) is settled as not speckle:
/// it has no surface, or it and its left neighbour have one and their relative distance is
/// within `t`. AVX-512F only.
std::uint32_t depthSettled16(const float* p, float t);

} // namespace afn
