// SPDX-License-Identifier: Apache-2.0
// The learned albedo trust (methods/afn/albedo_trust.h; weights with albedoTrust=1) of one 2 x 2
// block of the padded frame, run once the first encoder level e1 exists:
//   t = sigmoid(headG(e1))          at the block's half-resolution pixel: 3x3 over e1's half
//                                   values (zero outside e1), summed in float over the taps in
//                                   row order and the channels in order, then the bias
//   s = max(a, eps) / max(a + (1 - a) t, eps)   per channel of each of the block's 4 pixels, a the
//                                   albedo of x (the frame's, edge-replicated, as floats; 1 without
//                                   albedo)
// The block's TA colour times s is stored at the padded frame's size for the filtering (its
// padding differs from edge replication: t varies there), and the 2 x 2 average of the 1-spp
// colour times s replaces prepare's D(1-spp colour), summed in row order in float as the CPU's
// nn::down2. The network's output is divided by s again before the remodulation
// (conv_tile.h, outputValue()).
#pragma once

#include "cuda/device_math.h"

#include <cstddef>
#include <cstdint>

namespace afn::cuda {

constexpr int kTrustTaps = 9; ///< headG is 3x3

/// s of one channel (methods/afn/albedo_trust.cpp trustScale()).
AFN_HD float trustScale(float a, float t)
{
    const float blended = a + (1.0f - a) * t;
    return maxOf(a, kAlbedoEpsilonDevice) / maxOf(blended, kAlbedoEpsilonDevice);
}

/// Buffers of the albedo trust.
struct AlbedoTrustBuffers {
    int width = 0; ///< the frame
    int height = 0;
    int halfWidth = 0; ///< e1's size: half the padded frame
    int halfHeight = 0;
    const std::uint16_t* e1 = nullptr; ///< ReLU applied, `e1Stride` halves per pixel
    int e1Stride = 0;
    int e1Channels = 0; ///< headG's input channels
    /// headG's weights, [tap (ky * 3 + kx)][channel], then its bias (kTrustTaps * e1Channels + 1
    /// floats)
    const float* head = nullptr;
    const float* albedo = nullptr; ///< frame, 3 ch, or null (a = 1)
    const float* color1 = nullptr; ///< frame, 3 ch: the colour prepare pooled
    const float* colorTa = nullptr; ///< frame, 3 ch: the colour the TA branch filters
    float* trust = nullptr; ///< t, half the padded frame, 1 float per pixel
    float* colorTaScaled = nullptr; ///< padded frame, 3 floats per pixel
    float* color1Half = nullptr; ///< half the padded frame, 3 floats per pixel
};

/// t at half-resolution pixel (xh, yh).
AFN_HD float albedoTrustValue(const AlbedoTrustBuffers& b, int xh, int yh)
{
    float sum = 0.0f;
    for (int tap = 0; tap < kTrustTaps; ++tap) {
        const int qx = xh + tap % 3 - 1, qy = yh + tap / 3 - 1;
        if (qx < 0 || qy < 0 || qx >= b.halfWidth || qy >= b.halfHeight)
            continue;
        const std::uint16_t* e
            = b.e1 + (static_cast<std::size_t>(qy) * b.halfWidth + qx) * b.e1Stride;
        const float* w = b.head + tap * b.e1Channels;
        for (int c = 0; c < b.e1Channels; ++c)
            sum += loadFloat(w + c) * fromHalf(e[c]);
    }
    const float logit = sum + loadFloat(b.head + kTrustTaps * b.e1Channels);
    return 1.0f / (1.0f + expf(-logit));
}

/// The trust of block (xh, yh): t, the block's scaled TA colour and D(1-spp colour times s).
AFN_HD void albedoTrustBlock(const AlbedoTrustBuffers& b, int xh, int yh)
{
    const float t = albedoTrustValue(b, xh, yh);
    const std::size_t h = static_cast<std::size_t>(yh) * b.halfWidth + xh;
    b.trust[h] = t;
    const int paddedWidth = 2 * b.halfWidth;
    float sum1[3] = { 0.0f, 0.0f, 0.0f };
    for (int q = 0; q < 4; ++q) {
        const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
        const int sx = minOf(px, b.width - 1), sy = minOf(py, b.height - 1);
        const std::size_t s = static_cast<std::size_t>(sy) * b.width + sx;
        const std::size_t p = static_cast<std::size_t>(py) * paddedWidth + px;
        for (int c = 0; c < 3; ++c) {
            const float scale = trustScale(b.albedo ? b.albedo[3 * s + c] : 1.0f, t);
            b.colorTaScaled[3 * p + c] = b.colorTa[3 * s + c] * scale;
            sum1[c] += b.color1[3 * s + c] * scale;
        }
    }
    for (int c = 0; c < 3; ++c)
        b.color1Half[3 * h + c] = sum1[c] / 4.0f;
}

} // namespace afn::cuda
