// SPDX-License-Identifier: Apache-2.0
// Scalar helpers shared by the CUDA kernels and their host-side tests: the same source compiles
// for the device (nvcc) and for the CPU (any C++ compiler), so the per-pixel and per-lane code of
// the kernels is checked against the CPU engine on machines without a GPU.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__CUDACC__)
#include <cuda_fp16.h>
#define AFN_HD __host__ __device__ __forceinline__
#else
#include <cmath>
#define AFN_HD inline
#endif

#include "cuda/tensor_layout.h"

namespace afn::cuda {

/// Bits of a float.
AFN_HD std::uint32_t floatBits(float v)
{
#if defined(__CUDA_ARCH__)
    return __float_as_uint(v);
#else
    std::uint32_t u;
    std::memcpy(&u, &v, sizeof(u));
    return u;
#endif
}

/// The float with these bits.
AFN_HD float bitsFloat(std::uint32_t u)
{
#if defined(__CUDA_ARCH__)
    return __uint_as_float(u);
#else
    float v;
    std::memcpy(&v, &u, sizeof(v));
    return v;
#endif
}

/// True for a finite float (neither NaN nor +-Inf).
AFN_HD bool isFiniteFloat(float v)
{
    return (floatBits(v) & 0x7f800000u) != 0x7f800000u;
}

/// std::max / std::min semantics (the first argument wins ties and NaN comparisons).
AFN_HD float maxOf(float a, float b)
{
    return a < b ? b : a;
}
AFN_HD float minOf(float a, float b)
{
    return b < a ? b : a;
}

/// IEEE half from float (round to nearest even) and back.
AFN_HD std::uint16_t toHalf(float v)
{
#if defined(__CUDA_ARCH__)
    return __half_as_ushort(__float2half_rn(v));
#else
    return floatToHalf(v);
#endif
}
AFN_HD float fromHalf(std::uint16_t h)
{
#if defined(__CUDA_ARCH__)
    return __half2float(__ushort_as_half(h));
#else
    return halfToFloat(h);
#endif
}
/// Two halves in one word: `lo` in the low 16 bits.
AFN_HD std::uint32_t packHalves(float lo, float hi)
{
    return static_cast<std::uint32_t>(toHalf(lo)) | (static_cast<std::uint32_t>(toHalf(hi)) << 16);
}

/// A read-only 32-bit load (through the read-only data cache on the device).
AFN_HD std::uint32_t loadWord(const std::uint32_t* p)
{
#if defined(__CUDA_ARCH__)
    return __ldg(p);
#else
    return *p;
#endif
}
AFN_HD float loadFloat(const float* p)
{
#if defined(__CUDA_ARCH__)
    return __ldg(p);
#else
    return *p;
#endif
}

// ---- The CPU engine's scalar rules (stages/demodulate.h, methods/afn/network.h) -----------------

constexpr float kAlbedoEpsilonDevice = 1.0f / 1024.0f; ///< stages/demodulate.h kAlbedoEpsilon
constexpr float kMaxIrradianceDevice = 1e15f; ///< stages/demodulate.h kMaxIrradiance
constexpr float kDepthSkyDevice = 1e9f; ///< stages/feature_scaling.h kDepthSky

/// Divisor/multiplier of one albedo value (plain: the colour was demodulated by the renderer).
AFN_HD float albedoFactor(float albedo, bool plain)
{
    return plain ? albedo : maxOf(albedo, kAlbedoEpsilonDevice);
}
/// Irradiance clamped to [0, kMaxIrradiance]; NaN becomes 0.
AFN_HD float clampIrradiance(float v)
{
    return v > 0.0f ? minOf(v, kMaxIrradianceDevice) : 0.0f;
}
/// The radiance of an irradiance value for a model without albedo (methods/afn/network_inputs.cpp
/// undemodulate(): remodulated as stages/demodulate.cpp remodulate(), then at most
/// kMaxIrradiance).
AFN_HD float undemodulateValue(float irradiance, float albedo, bool plain)
{
    return minOf(clampIrradiance(irradiance) * albedoFactor(albedo, plain), kMaxIrradianceDevice);
}
/// T(x) = clip(max(x, 0)^(1/2.2), 0, 1).
AFN_HD float toneMap(float x)
{
    return minOf(maxOf(powf(maxOf(x, 0.0f), 1.0f / 2.2f), 0.0f), 1.0f);
}

} // namespace afn::cuda
