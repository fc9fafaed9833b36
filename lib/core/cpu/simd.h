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

namespace afn::cpu {

typedef float V8 __attribute__((vector_size(32)));
typedef float V8u __attribute__((vector_size(32), aligned(4))); ///< unaligned access
typedef std::int32_t I8 __attribute__((vector_size(32)));

inline __attribute__((always_inline)) V8 load8(const float* p)
{
    return *reinterpret_cast<const V8u*>(p);
}
inline __attribute__((always_inline)) void store8(float* p, V8 v)
{
    *reinterpret_cast<V8u*>(p) = v;
}
inline __attribute__((always_inline)) V8 splat8(float v)
{
    return V8 { v, v, v, v, v, v, v, v };
}

/// exp(x) for x <= 0 (softmax after max subtraction), about 2 ulp (Cephes expf polynomial);
/// x below -87 gives exp(-87) ~ 1.6e-38 instead of a denormal or 0.
inline __attribute__((always_inline)) V8 exp8(V8 x)
{
    const V8 lo = splat8(-87.0f);
    x = x < lo ? lo : x;
    const V8 magic = splat8(12582912.0f); // 1.5 * 2^23: round to nearest integer
    const V8 t = x * splat8(1.44269504088896341f) + magic;
    const V8 n = t - magic;
    const V8 r = x - n * splat8(0.693359375f) - n * splat8(-2.12194440e-4f);
    V8 p = splat8(1.9875691500e-4f);
    p = p * r + splat8(1.3981999507e-3f);
    p = p * r + splat8(8.3334519073e-3f);
    p = p * r + splat8(4.1665795894e-2f);
    p = p * r + splat8(1.6666665459e-1f);
    p = p * r + splat8(5.0000001201e-1f);
    p = p * r * r + r + splat8(1.0f);
    I8 ti;
    std::memcpy(&ti, &t, sizeof(ti));
    I8 tm;
    std::memcpy(&tm, &magic, sizeof(tm));
    const I8 bits = (ti - tm + 127) << 23; // 2^n
    V8 scale;
    std::memcpy(&scale, &bits, sizeof(scale));
    return p * scale;
}

} // namespace afn::cpu

#pragma GCC diagnostic pop
