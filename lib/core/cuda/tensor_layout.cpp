// SPDX-License-Identifier: Apache-2.0
// Half-precision conversion and weight packing of the CUDA AFN engine (see tensor_layout.h).
#include "cuda/tensor_layout.h"

#include "base/exception.h"
#include "nn/conv.h"

#include <cstring>

namespace afn::cuda {

std::uint16_t floatToHalf(float v)
{
    std::uint32_t f;
    std::memcpy(&f, &v, sizeof(f));
    const std::uint32_t sign = (f >> 16) & 0x8000u;
    const std::uint32_t absBits = f & 0x7fffffffu;
    if (absBits >= 0x7f800000u) // Inf or NaN (NaN keeps a quiet payload bit)
        return static_cast<std::uint16_t>(sign | 0x7c00u | (absBits > 0x7f800000u ? 0x200u : 0u));
    if (absBits >= 0x477ff000u) // rounds to 65520 or more: overflow to infinity
        return static_cast<std::uint16_t>(sign | 0x7c00u);
    const int exponent = static_cast<int>(absBits >> 23) - 127;
    if (exponent >= -14) {
        // Normal half: keep 10 mantissa bits, round to nearest even on the 13 dropped ones.
        const std::uint32_t mantissa = absBits & 0x7fffffu;
        std::uint32_t h = (static_cast<std::uint32_t>(exponent + 15) << 10) | (mantissa >> 13);
        const std::uint32_t rest = mantissa & 0x1fffu;
        if (rest > 0x1000u || (rest == 0x1000u && (h & 1u)))
            ++h; // a carry into the exponent is the correct rounding
        return static_cast<std::uint16_t>(sign | h);
    }
    if (exponent < -25) // below half the smallest subnormal: zero
        return static_cast<std::uint16_t>(sign);
    // Subnormal half: value = m * 2^-24 with m = significand * 2^(exponent + 1) (24-bit
    // significand), rounded to nearest even.
    const std::uint32_t significand = (absBits & 0x7fffffu) | 0x800000u;
    const int shift = -exponent - 1; // 14..24 bits dropped
    std::uint32_t h = significand >> shift;
    const std::uint32_t rest = significand & ((1u << shift) - 1u);
    const std::uint32_t halfway = 1u << (shift - 1);
    if (rest > halfway || (rest == halfway && (h & 1u)))
        ++h;
    return static_cast<std::uint16_t>(sign | h);
}

float halfToFloat(std::uint16_t h)
{
    const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000u) << 16;
    const std::uint32_t exponent = (h >> 10) & 0x1fu;
    std::uint32_t mantissa = h & 0x3ffu;
    std::uint32_t f;
    if (exponent == 0x1fu) {
        f = sign | 0x7f800000u | (mantissa << 13);
    } else if (exponent != 0) {
        f = sign | ((exponent + 112u) << 23) | (mantissa << 13);
    } else if (mantissa == 0) {
        f = sign;
    } else {
        // Subnormal: normalise the mantissa.
        int e = 113;
        while (!(mantissa & 0x400u)) {
            mantissa <<= 1;
            --e;
        }
        f = sign | (static_cast<std::uint32_t>(e) << 23) | ((mantissa & 0x3ffu) << 13);
    }
    float v;
    std::memcpy(&v, &f, sizeof(v));
    return v;
}

PackedConv packConv(const nn::Conv& conv, int upChannels)
{
    if (!conv.loaded() || upChannels < 0 || upChannels > conv.inChannels())
        throwInvalidOperation("CUDA AFN: cannot pack an unloaded or mismatched layer");
    PackedConv p;
    p.ksize = conv.kernelSize();
    p.upChannels = upChannels;
    p.sameChannels = conv.inChannels() - upChannels;
    p.outChannels = conv.outChannels();
    const int taps = p.ksize * p.ksize, kChunks = p.kChunks(), tiles = p.tiles();
    const int nPad = tiles * kTileN, in = conv.inChannels(), cp = conv.paddedOutChannels();
    const float* wp = conv.paddedWeights(); // [tap][ci][co padded to 8]
    auto weight = [&](int tap, int ci, int co) {
        return wp[(static_cast<std::size_t>(tap) * in + ci) * cp + co];
    };
    // Input channel of element k of chunk kc, or -1 in the padding.
    auto inputChannel = [&](int kc, int k) {
        if (kc < p.upChunks()) {
            const int c = kc * kChunk + k;
            return c < p.upChannels ? c : -1;
        }
        const int c = (kc - p.upChunks()) * kChunk + k;
        return c < p.sameChannels ? p.upChannels + c : -1;
    };
    p.weights.assign(static_cast<std::size_t>(taps) * kChunks * nPad * 8, 0u);
    for (int tap = 0; tap < taps; ++tap)
        for (int kc = 0; kc < kChunks; ++kc)
            for (int n = 0; n < p.outChannels; ++n)
                for (int w = 0; w < 8; ++w) {
                    std::uint32_t word = 0;
                    for (int e = 0; e < 2; ++e) {
                        const int ci = inputChannel(kc, 2 * w + e);
                        const std::uint16_t h = ci < 0 ? 0 : floatToHalf(weight(tap, ci, n));
                        word |= static_cast<std::uint32_t>(h) << (16 * e);
                    }
                    p.weights[packedWeightIndex(tap, kc, n, w, kChunks, tiles)] = word;
                }
    p.bias.assign(nPad, 0.0f);
    std::memcpy(p.bias.data(), conv.paddedBias(), sizeof(float) * p.outChannels);
    return p;
}

std::vector<float> packTrustHead(const nn::Conv& conv)
{
    if (!conv.loaded() || conv.kernelSize() != 3 || conv.outChannels() != 1)
        throwInvalidOperation("CUDA AFN: the albedo trust's head is not a 3x3 layer with 1 output");
    const int in = conv.inChannels(), cp = conv.paddedOutChannels();
    const float* wp = conv.paddedWeights(); // [tap][ci][co padded to 8]
    std::vector<float> packed(static_cast<std::size_t>(9) * in + 1);
    for (int tap = 0; tap < 9; ++tap)
        for (int ci = 0; ci < in; ++ci)
            packed[static_cast<std::size_t>(tap) * in + ci]
                = wp[(static_cast<std::size_t>(tap) * in + ci) * cp];
    packed.back() = conv.paddedBias()[0];
    return packed;
}

} // namespace afn::cuda
