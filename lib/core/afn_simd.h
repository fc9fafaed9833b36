// SPDX-License-Identifier: Apache-2.0
// 8-wide float vectors for the AFN engine (GCC/Clang vector extensions; two SSE registers on
// baseline x86-64, one AVX register in functions compiled for x86-64-v3) and a vector exp.
#pragma once

#include <cstdint>
#include <cstring>

// The helpers below are always inlined into functions of one target, so the AVX-vector ABI note
// (-Wpsabi) does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn {

typedef float AfnV8 __attribute__((vector_size(32)));
typedef float AfnV8u __attribute__((vector_size(32), aligned(4))); ///< unaligned access
typedef std::int32_t AfnI8 __attribute__((vector_size(32)));

inline __attribute__((always_inline)) AfnV8 afnLoad8(const float* p)
{
    return *reinterpret_cast<const AfnV8u*>(p);
}
inline __attribute__((always_inline)) void afnStore8(float* p, AfnV8 v)
{
    *reinterpret_cast<AfnV8u*>(p) = v;
}
inline __attribute__((always_inline)) AfnV8 afnSplat8(float v)
{
    return AfnV8 { v, v, v, v, v, v, v, v };
}

/// exp(x) for x <= 0 (softmax after max subtraction), about 2 ulp (Cephes expf polynomial);
/// x below -87 gives exp(-87) ~ 1.6e-38 instead of a denormal or 0.
inline __attribute__((always_inline)) AfnV8 afnExp8(AfnV8 x)
{
    const AfnV8 lo = afnSplat8(-87.0f);
    x = x < lo ? lo : x;
    const AfnV8 magic = afnSplat8(12582912.0f); // 1.5 * 2^23: round to nearest integer
    const AfnV8 t = x * afnSplat8(1.44269504088896341f) + magic;
    const AfnV8 n = t - magic;
    const AfnV8 r = x - n * afnSplat8(0.693359375f) - n * afnSplat8(-2.12194440e-4f);
    AfnV8 p = afnSplat8(1.9875691500e-4f);
    p = p * r + afnSplat8(1.3981999507e-3f);
    p = p * r + afnSplat8(8.3334519073e-3f);
    p = p * r + afnSplat8(4.1665795894e-2f);
    p = p * r + afnSplat8(1.6666665459e-1f);
    p = p * r + afnSplat8(5.0000001201e-1f);
    p = p * r * r + r + afnSplat8(1.0f);
    AfnI8 ti;
    std::memcpy(&ti, &t, sizeof(ti));
    AfnI8 tm;
    std::memcpy(&tm, &magic, sizeof(tm));
    const AfnI8 bits = (ti - tm + 127) << 23; // 2^n
    AfnV8 scale;
    std::memcpy(&scale, &bits, sizeof(scale));
    return p * scale;
}

} // namespace afn

#pragma GCC diagnostic pop
