// SPDX-License-Identifier: Apache-2.0
// The network input of one 2 x 2 block of the padded frame (methods/afn/network.cpp prepare() and
// the first pooling of predict(), stages/feature_scaling.cpp): for each of the four pixels, read
// with edge replication from the frame, x = [T(c1), T(cTA), albedo, normal01, depth01] (13
// channels), with history01 as a 14th for weights with the history input (methods/afn/network.h),
// stored as halves with zero channels up to 16; the block's 2 x 2 average of x (the encoder's
// input) and of the 1-spp colour (filtered at half resolution), both averaged in float before any
// rounding, as the CPU does.
#pragma once

#include "cuda/device_math.h"

namespace afn::cuda {

constexpr int kInputChannels = 13; ///< channels of the network input x
constexpr int kHistoryInputChannels = 14; ///< with history01 (weights with history=1)
constexpr int kInputStride = 16; ///< channelStride(kInputChannels), as of kHistoryInputChannels
constexpr float kMaxHistoryLengthDevice = 255.0f; ///< stages/temporal_accumulation.h

/// Order-preserving unsigned key of a float: a < b exactly when key(a) < key(b) (for atomic
/// min/max of floats).
AFN_HD std::uint32_t orderedKey(float v)
{
    const std::uint32_t u = floatBits(v);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
AFN_HD float fromOrderedKey(std::uint32_t k)
{
    return bitsFloat((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}
/// Keys of an empty depth range: min = largest key, max = smallest key.
constexpr std::uint32_t kEmptyRangeMin = 0xffffffffu;
constexpr std::uint32_t kEmptyRangeMax = 0u;

/// A depth that counts for the per-frame range (stages/feature_scaling.h: finite and closer than
/// the sky).
AFN_HD bool isValidDepth(float z)
{
    return isFiniteFloat(z) && fabsf(z) < kDepthSkyDevice;
}

/// Per-frame depth normalisation: depth01 = clamp((z - lo) * scale, 0, 1); invalid depth -> 1.
struct DepthScale {
    float lo = 0.0f;
    float scale = 0.0f;
};

/// The scale of a range given as ordered keys (stages/feature_scaling.cpp depthToUnitRange).
AFN_HD DepthScale depthScale(std::uint32_t minKey, std::uint32_t maxKey)
{
    DepthScale s;
    if (minKey == kEmptyRangeMin) // no valid depth in the frame
        return s;
    const float lo = fromOrderedKey(minKey), hi = fromOrderedKey(maxKey);
    s.lo = lo;
    s.scale = hi > lo ? static_cast<float>(1.0 / (static_cast<double>(hi) - lo)) : 0.0f;
    return s;
}

AFN_HD float depthToUnit(float z, const DepthScale& s)
{
    const float v = isValidDepth(z) ? (z - s.lo) * s.scale : 1.0f;
    return minOf(maxOf(v, 0.0f), 1.0f);
}

AFN_HD float normalToUnit(float n)
{
    return isFiniteFloat(n) ? minOf(maxOf(n * 0.5f + 0.5f, 0.0f), 1.0f) : 0.5f;
}

/// history01 of a pixel whose history holds n frames (methods/afn/network_inputs.cpp
/// makeHistory01): 1 / n, at least 1 / kMaxHistoryLength; 1 for n <= 1 or NaN (no history).
AFN_HD float historyToUnit(float n)
{
    return n > 1.0f ? maxOf(1.0f / n, 1.0f / kMaxHistoryLengthDevice) : 1.0f;
}

/// Buffers of the input preparation.
struct PrepareBuffers {
    int width = 0; ///< the frame
    int height = 0;
    int paddedWidth = 0; ///< paddedSize(width)
    int paddedHeight = 0;
    const float* color1 = nullptr; ///< 3 ch: the 1-spp irradiance (variant "ta": the TA colour)
    const float* colorTa = nullptr; ///< 3 ch: the TA colour (variant "1spp": the irradiance)
    const float* albedo = nullptr; ///< 3 ch or null (1)
    const float* normal = nullptr; ///< 3 ch or null (normal01 = 0.5)
    const float* depth = nullptr; ///< 1 ch or null (depth01 = 0)
    const std::uint32_t* depthRange = nullptr; ///< ordered keys of the valid depths' min, max
    /// x has the 14th channel history01 (weights with the history input)
    int historyChannel = 0;
    /// 1 ch, the frames the TA colour holds (history01 = historyToUnit); null: history01 = 1
    /// (a network run without its temporal branch)
    const float* historyLength = nullptr;
    std::uint16_t* x = nullptr; ///< padded frame, kInputStride halves per pixel
    std::uint16_t* xHalf = nullptr; ///< half of the padded frame, kInputStride halves per pixel
    float* color1Half = nullptr; ///< half of the padded frame, 3 floats per pixel
};

/// Prepare block (xh, yh) of the half-resolution grid.
AFN_HD void prepareBlock(const PrepareBuffers& b, const DepthScale& ds, int xh, int yh)
{
    const int channels = b.historyChannel ? kHistoryInputChannels : kInputChannels;
    float sum[kHistoryInputChannels] = {};
    float sum1[3] = { 0.0f, 0.0f, 0.0f };
    for (int q = 0; q < 4; ++q) {
        const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
        const int sx = minOf(px, b.width - 1), sy = minOf(py, b.height - 1);
        const std::size_t s = static_cast<std::size_t>(sy) * b.width + sx;
        float v[kHistoryInputChannels];
        for (int c = 0; c < 3; ++c) {
            const float c1 = b.color1[3 * s + c];
            v[c] = toneMap(c1);
            v[3 + c] = toneMap(b.colorTa[3 * s + c]);
            v[6 + c] = b.albedo ? b.albedo[3 * s + c] : 1.0f;
            v[9 + c] = b.normal ? normalToUnit(b.normal[3 * s + c]) : 0.5f;
            sum1[c] += c1;
        }
        v[12] = b.depth ? depthToUnit(b.depth[s], ds) : 0.0f;
        v[13] = b.historyLength ? historyToUnit(b.historyLength[s]) : 1.0f;
        std::uint32_t words[kInputStride / 2];
        for (int w = 0; w < kInputStride / 2; ++w) {
            const int c = 2 * w;
            words[w] = packHalves(c < channels ? v[c] : 0.0f, c + 1 < channels ? v[c + 1] : 0.0f);
        }
        std::uint32_t* dst = reinterpret_cast<std::uint32_t*>(
            b.x + (static_cast<std::size_t>(py) * b.paddedWidth + px) * kInputStride);
        for (int w = 0; w < kInputStride / 2; ++w)
            dst[w] = words[w];
        for (int c = 0; c < channels; ++c)
            sum[c] += v[c];
    }
    const std::size_t h = static_cast<std::size_t>(yh) * (b.paddedWidth / 2) + xh;
    std::uint32_t* dst = reinterpret_cast<std::uint32_t*>(b.xHalf + h * kInputStride);
    for (int w = 0; w < kInputStride / 2; ++w) {
        const int c = 2 * w;
        dst[w] = packHalves(
            c < channels ? sum[c] / 4.0f : 0.0f, c + 1 < channels ? sum[c + 1] / 4.0f : 0.0f);
    }
    for (int c = 0; c < 3; ++c)
        b.color1Half[3 * h + c] = sum1[c] / 4.0f;
}

} // namespace afn::cuda
