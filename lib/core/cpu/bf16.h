// SPDX-License-Identifier: Apache-2.0
// bfloat16 values of the reduced-precision convolutions (cpu/conv_avx512_bf16.cpp): the upper 16
// bits of an IEEE float32 (8 exponent bits, 7 mantissa bits), rounded to nearest even as the
// processor's VCVTNE2PS2BF16 does. NaN stays NaN (quiet).
#pragma once

#include <cstdint>
#include <cstring>

namespace afn::cpu {

/// float32 -> bfloat16, round to nearest even; NaN -> quiet NaN of the same sign.
inline std::uint16_t toBf16(float v)
{
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    if ((u & 0x7F800000u) == 0x7F800000u && (u & 0x007FFFFFu))
        return static_cast<std::uint16_t>((u >> 16) | 0x0040u);
    u += 0x7FFFu + ((u >> 16) & 1u);
    return static_cast<std::uint16_t>(u >> 16);
}

/// bfloat16 -> float32 (exact).
inline float fromBf16(std::uint16_t b)
{
    const std::uint32_t u = static_cast<std::uint32_t>(b) << 16;
    float v;
    std::memcpy(&v, &u, 4);
    return v;
}

} // namespace afn::cpu
