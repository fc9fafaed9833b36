// SPDX-License-Identifier: Apache-2.0
// Per-lane pieces of the fused kernel-prediction heads, softmax, 7 x 7 filtering and fusion
// (methods/afn/fusion.h). A head's 56 accumulators of one pixel (49 taps, the alpha logit, 6 pad
// columns, as 7 N tiles) are spread over the 4 lanes of a quad: lane t of the quad holds columns
// 8 nt + 2t and 8 nt + 2t + 1 (fragment.h). Each lane reduces over its own taps; the kernel then
// combines the quad's 4 partial results (filter_fuse.cu), and the host tests do the same with an
// emulated warp.
#pragma once

#include "cuda/conv_tile.h"

namespace afn::cuda {

constexpr int kKernelSize = 7;
constexpr int kKernelTaps = 49;
constexpr int kHeadTiles = 7; ///< N tiles of a head (49 or 50 columns, padded to 56)
constexpr int kAlphaColumn = 49; ///< headTA's alpha logit
constexpr int kRefineInputChannels = 10; ///< T(i) 3, albedo 3, normal01 3, depth01 1

/// Accumulators of one head for the 16 rows of a tile, as a lane holds them.
struct HeadAccumulators {
    float v[kHeadTiles][4];
};

/// Tap (0..48) of accumulator element i of N tile nt in `lane`, or -1 (alpha logit, padding).
AFN_HD int tapOf(int lane, int nt, int i)
{
    const int j = nt * kTileN + Fragment::cCol(lane, i);
    return j < kKernelTaps ? j : -1;
}

/// Add the head's bias to every accumulator (logits).
AFN_HD void addHeadBias(HeadAccumulators& h, const float* bias, int lane)
{
    for (int nt = 0; nt < kHeadTiles; ++nt)
        for (int i = 0; i < 4; ++i)
            h.v[nt][i] += loadFloat(bias + nt * kTileN + Fragment::cCol(lane, i));
}

/// Largest logit among this lane's taps of tile row half `half` (0: rows g, 1: rows g + 8).
AFN_HD float lanePartialMax(const HeadAccumulators& h, int lane, int half)
{
    float m = -3.402823466e38f;
    for (int nt = 0; nt < kHeadTiles; ++nt)
        for (int e = 0; e < 2; ++e)
            if (tapOf(lane, nt, 2 * half + e) >= 0)
                m = maxOf(m, h.v[nt][2 * half + e]);
    return m;
}

/// Replace this lane's logits of row half `half` by exp(logit - max); returns their sum.
AFN_HD float laneExpSum(HeadAccumulators& h, int lane, int half, float max)
{
    float s = 0.0f;
    for (int nt = 0; nt < kHeadTiles; ++nt)
        for (int e = 0; e < 2; ++e)
            if (tapOf(lane, nt, 2 * half + e) >= 0) {
                float& v = h.v[nt][2 * half + e];
                v = expf(v - max);
                s += v;
            }
    return s;
}

/// Zero outside the padded frame, else the frame's pixel with edge replication (the padded TA
/// colour of network.cpp prepare(), never stored).
struct PaddedColor {
    const float* data = nullptr; ///< frame size, 3 floats per pixel
    int width = 0; ///< the frame
    int height = 0;
    int paddedWidth = 0;
    int paddedHeight = 0;
    AFN_HD void fetch(int x, int y, float (&rgb)[3]) const
    {
        if (x < 0 || y < 0 || x >= paddedWidth || y >= paddedHeight) {
            rgb[0] = rgb[1] = rgb[2] = 0.0f;
            return;
        }
        const std::size_t i
            = static_cast<std::size_t>(minOf(y, height - 1)) * width + minOf(x, width - 1);
        for (int c = 0; c < 3; ++c)
            rgb[c] = loadFloat(data + 3 * i + c);
    }
};

/// Zero outside, else the pixel (the half-resolution 1-spp colour).
struct PlainColor {
    const float* data = nullptr; ///< 3 floats per pixel
    int width = 0;
    int height = 0;
    AFN_HD void fetch(int x, int y, float (&rgb)[3]) const
    {
        if (x < 0 || y < 0 || x >= width || y >= height) {
            rgb[0] = rgb[1] = rgb[2] = 0.0f;
            return;
        }
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        for (int c = 0; c < 3; ++c)
            rgb[c] = loadFloat(data + 3 * i + c);
    }
};

/// This lane's share of the 7 x 7 filtering at (x, y): sum over its taps j of
/// exp-logit_j * inv * colour(x + j % 7 - 3, y + j / 7 - 3).
template <typename Color>
AFN_HD void laneFilter(const HeadAccumulators& h, int lane, int half, float inv, const Color& color,
    int x, int y, float (&rgb)[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    for (int nt = 0; nt < kHeadTiles; ++nt)
        for (int e = 0; e < 2; ++e) {
            const int j = tapOf(lane, nt, 2 * half + e);
            if (j < 0)
                continue;
            const float w = h.v[nt][2 * half + e] * inv;
            float px[3];
            color.fetch(x + j % kKernelSize - 3, y + j / kKernelSize - 3, px);
            for (int c = 0; c < 3; ++c)
                rgb[c] += w * px[c];
        }
}

/// Sigmoid of the alpha logit.
AFN_HD float sigmoid(float v)
{
    return 1.0f / (1.0f + expf(-v));
}

/// Eq. 3 for one pixel of a 2 x 2 block: i = dTA - alpha * mean(block dTA) + alpha * d1spp, the
/// block mean summed in row order (TL, TR, BL, BR) then divided by 4 (avg_pool2d).
AFN_HD float fuse(float dTa, float alpha, float tl, float tr, float bl, float br, float d1)
{
    const float mean = (tl + tr + bl + br) / 4.0f;
    return dTa - alpha * mean + alpha * d1;
}

/// Element c of a 3-vector for a run-time c (selects, so that the vector stays in registers).
AFN_HD float component(const float (&v)[3], int c)
{
    return c == 0 ? v[0] : (c == 1 ? v[1] : v[2]);
}

/// Refinement input channel c (0..15, kRefineInputChannels used) of a pixel: T(i) (3), then x's
/// albedo, normal01 and depth01 (x channels 6..12), then zeros. `xPixel` points to the pixel's
/// 16 x halves.
AFN_HD std::uint16_t refineInputChannel(int c, const float (&fused)[3], const std::uint16_t* xPixel)
{
    if (c < 3)
        return toHalf(toneMap(component(fused, c)));
    if (c < kRefineInputChannels)
        return xPixel[c + 3];
    return 0;
}

/// Operands of the fused heads + filtering + fusion kernel.
struct FilterFuseArgs {
    ConvOperands head1; ///< 1x1 on d1 (half resolution, Row16 tiles)
    ConvOperands headTa; ///< 1x1 on concat(U(d1), x) (full resolution, Block8x2 tiles)
    const std::uint16_t* x = nullptr; ///< network input, padded frame, 16 halves per pixel
    PaddedColor colorTa; ///< filtered at full resolution
    PlainColor color1Half; ///< D(1-spp colour), filtered at half resolution
    // With refinement: the fused image and the refinement input.
    float* fused = nullptr; ///< padded frame, 3 floats per pixel
    std::uint16_t* refineInput = nullptr; ///< padded frame, 16 halves per pixel
    // Without refinement (variants fusion, 1spp, ta): the output.
    FinalOutput output; ///< used when `fused` is null (output.fused unused)
};

} // namespace afn::cuda
