// SPDX-License-Identifier: Apache-2.0
// Internal to stages/reproject.cpp: the AVX-512 acceptance test of identity rows
// (reproject_avx512.cpp).
#pragma once

#include <cstdint>

namespace afn {

/// 16 consecutive pixels of an identity row: packed 3-float pixels of this frame and the
/// previous one at the same pixels (normal pointers unused when `testNormal` is false).
struct IdentityRow16 {
    const float* position;
    const float* prevPosition;
    const float* normal;
    const float* prevNormal;
    bool testNormal = false; ///< the normal test applies
    float normalLimitSquared = 0.0f;
};

/// Per lane: bit set in `accepted` (own tap accepted) or `rejected` (own tap rejected); lanes in
/// neither are left to the scalar test.
struct IdentityDecision {
    std::uint32_t accepted = 0;
    std::uint32_t rejected = 0;
};

/// The identity-row test of 16 pixels for a relative position test (positions in both frames,
/// positionLimitSquared = 0). AVX-512F only (cpu::activeIsa() == Avx512).
IdentityDecision identityTaps16(const IdentityRow16& row);

} // namespace afn
