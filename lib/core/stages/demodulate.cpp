// SPDX-License-Identifier: Apache-2.0
// Albedo demodulation and remodulation (see stages/demodulate.h for the convention).
#include "stages/demodulate.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "stages/demodulate_avx512.h"

#include <algorithm>

namespace afn {

namespace {

/// Divisor/multiplier for one albedo value.
inline float albedoFactor(float albedo, bool plain)
{
    return plain ? albedo : std::max(albedo, kAlbedoEpsilon);
}

/// Clamp to [0, kMaxIrradiance]; NaN becomes 0 (the gather already sanitised, this is a backstop).
inline float clampIrradiance(float v)
{
    return v > 0.0f ? std::min(v, kMaxIrradiance) : 0.0f;
}

} // namespace

void demodulateRows(const Frame& frame, Image& irradiance, int y0, int y1)
{
    const bool divide = frame.hasAlbedo() && !frame.colorDemodulated;
    const int n = 3 * frame.width; // rows are packed: one run of floats per row (vectorised)
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    for (int y = y0; y < y1; ++y) {
        const float* c = frame.color.at(0, y);
        float* o = irradiance.at(0, y);
        if (avx512) { // 16 values at a time, the same operations (demodulate_avx512.cpp)
            demodulateRunAvx512(c, divide ? frame.albedo.at(0, y) : nullptr, o, n);
        } else if (divide) {
            const float* a = frame.albedo.at(0, y);
            for (int i = 0; i < n; ++i)
                o[i] = clampIrradiance(c[i] / albedoFactor(a[i], false));
        } else {
            for (int i = 0; i < n; ++i)
                o[i] = clampIrradiance(c[i]);
        }
    }
}

void demodulate(const Frame& frame, Image& irradiance)
{
    irradiance.resize(frame.width, frame.height, 3);
    parallelRows(frame.height, [&](int y0, int y1) { demodulateRows(frame, irradiance, y0, y1); });
}

void remodulateRow(const Frame& frame, const Image& irradiance, int y, std::byte* out,
    std::ptrdiff_t pixelStride, bool toCaller)
{
    const float* i = irradiance.at(0, y);
    const int w = frame.width;
    if (!frame.hasAlbedo()) {
        for (int x = 0; x < w; ++x, out += pixelStride) {
            float* o = reinterpret_cast<float*>(out);
            for (int k = 0; k < 3; ++k)
                o[k] = clampIrradiance(i[3 * x + k]) * 1.0f;
        }
        return;
    }
    const float* a = frame.albedo.at(0, y);
    const bool plain = frame.colorDemodulated;
    if (pixelStride == static_cast<std::ptrdiff_t>(3 * sizeof(float))) {
        // Packed output: one run of floats (vectorised), the same operations.
        float* o = reinterpret_cast<float*>(out);
        if (cpu::activeIsa() == cpu::Isa::Avx512) {
            remodulateRunAvx512(i, a, o, 3 * w, plain, toCaller);
            return;
        }
        for (int k = 0; k < 3 * w; ++k)
            o[k] = clampIrradiance(i[k]) * albedoFactor(a[k], plain);
        return;
    }
    for (int x = 0; x < w; ++x, out += pixelStride) {
        float* o = reinterpret_cast<float*>(out);
        for (int k = 0; k < 3; ++k)
            o[k] = clampIrradiance(i[3 * x + k]) * albedoFactor(a[3 * x + k], plain);
    }
}

float albedoFactorAt(const Frame& frame, int x, int y, int k)
{
    return frame.hasAlbedo() ? albedoFactor(frame.albedo(x, y, k), frame.colorDemodulated) : 1.0f;
}

void remodulate(const Frame& frame, const Image& irradiance, Image& radiance)
{
    if (&radiance != &irradiance)
        radiance.resize(frame.width, frame.height, 3);
    const std::ptrdiff_t stride = 3 * sizeof(float);
    parallelRows(frame.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            remodulateRow(
                frame, irradiance, y, reinterpret_cast<std::byte*>(radiance.at(0, y)), stride);
    });
}

} // namespace afn
