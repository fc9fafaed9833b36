// SPDX-License-Identifier: Apache-2.0
// Per-thread code of AFN large on the CUDA engine (methods/afn/network_large.cpp, the graph of
// training/afn/model_large.py), one piece per kernel of large.cu:
//   largePrepareBlock     x = [T(c), albedo, normal01, depth01] (10 ch, halves, stride 16) and c
//                         (the colour, float) at the padded size with edge replication, their
//                         2 x 2 averages (the encoder's input; D(c)) in float before rounding
//   down2Pixel            D of a float image (D(D(c)))
//   largeFilterPixel      softmax over a head's 25 logits, the 5 x 5 kernel applied to a scale's
//                         colour with edge replication, taps summed in index order
//   fuseScalesBlock       Eq. 3 between two scales (nn/scale_fusion.cpp), in place on the fine one
//   largeRefineInputPixel a refinement module's input [T(o), albedo, normal01, depth01] (halves)
// The convolutions (U-Net, the three 1x1 heads with float outputs, the refinement modules) run on
// the tensor cores as AFN's (conv_tile.h). Compiled with --fmad=false like the CPU's arithmetic.
#pragma once

#include "cuda/conv_tile.h"
#include "cuda/device_math.h"
#include "cuda/prepare_block.h"

#include <cstddef>
#include <cstdint>

namespace afn::cuda {

constexpr int kLargeInputChannels = 10; ///< T(c) 3, albedo 3, normal01 3, depth01 1
constexpr int kLargeInputStride = 16; ///< channelStride(kLargeInputChannels)
constexpr int kLargeKernelSize = 5;
constexpr int kLargeTaps = kLargeKernelSize * kLargeKernelSize;

/// What AFN large reads of a frame (frame size; null: the neutral value).
struct LargeSources {
    int width = 0;
    int height = 0;
    const float* color = nullptr; ///< 3 ch, the colour filtered (the 1-spp/high-spp irradiance)
    const float* albedo = nullptr;
    const float* normal = nullptr;
    const float* depth = nullptr;
    const std::uint32_t* depthRange = nullptr; ///< the frame's valid depths (prepare_block.h)
};

/// Buffers of the input preparation (sizes as PrepareBuffers).
struct LargePrepareBuffers {
    int width = 0; ///< the frame
    int height = 0;
    int paddedWidth = 0;
    int paddedHeight = 0;
    const float* color = nullptr; ///< 3 ch, the colour the network filters (frame size)
    const float* albedo = nullptr; ///< 3 ch or null (1)
    const float* normal = nullptr; ///< 3 ch or null (normal01 = 0.5)
    const float* depth = nullptr; ///< 1 ch or null (depth01 = 0)
    const std::uint32_t* depthRange = nullptr; ///< PrepareBuffers::depthRange
    std::uint16_t* x = nullptr; ///< padded frame, kLargeInputStride halves per pixel
    std::uint16_t* xHalf = nullptr; ///< half the padded frame, kLargeInputStride halves per pixel
    float* c = nullptr; ///< padded frame, 3 floats per pixel
    float* cHalf = nullptr; ///< half the padded frame, 3 floats per pixel
};

/// AFN large's refinement (methods/afn/network_large.cpp): modules of three layers, each module
/// refining the previous one's output.
constexpr int kLargeRefineModules = 2;
constexpr int kLargeRefineLayers = 3;

/// Where refinement module m, whose input is `o`, writes: a module before the last at the padded
/// size, demodulated, into `refined` (the next module's input); the last one into the frame's
/// output `out`, every row computed, without the albedo trust.
inline FinalOutput largeRefinementOutput(int m, const FinalOutput& out, float* refined,
    int paddedWidth, int paddedHeight, const float* o)
{
    FinalOutput fo;
    if (m + 1 < kLargeRefineModules) {
        fo.data = refined;
        fo.width = paddedWidth;
        fo.height = paddedHeight;
        fo.demodulated = 1;
    } else {
        fo = out;
        fo.computedRows = nullptr;
        fo.trust = nullptr;
    }
    fo.fused = o;
    return fo;
}

/// The preparation's buffers: frame `s` padded to paddedWidth x paddedHeight, into x, xHalf, c and
/// cHalf (the device graph's buffers, or the host emulation's).
inline LargePrepareBuffers largePrepareBuffers(const LargeSources& s, int paddedWidth,
    int paddedHeight, std::uint16_t* x, std::uint16_t* xHalf, float* c, float* cHalf)
{
    LargePrepareBuffers b;
    b.width = s.width;
    b.height = s.height;
    b.paddedWidth = paddedWidth;
    b.paddedHeight = paddedHeight;
    b.color = s.color;
    b.albedo = s.albedo;
    b.normal = s.normal;
    b.depth = s.depth;
    b.depthRange = s.depthRange;
    b.x = x;
    b.xHalf = xHalf;
    b.c = c;
    b.cHalf = cHalf;
    return b;
}

/// Block (xh, yh) of the half-resolution grid.
AFN_HD void largePrepareBlock(const LargePrepareBuffers& b, const DepthScale& ds, int xh, int yh)
{
    float sum[kLargeInputChannels] = {};
    float sumC[3] = { 0.0f, 0.0f, 0.0f };
    for (int q = 0; q < 4; ++q) {
        const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
        const int sx = minOf(px, b.width - 1), sy = minOf(py, b.height - 1);
        const std::size_t s = static_cast<std::size_t>(sy) * b.width + sx;
        const std::size_t d = static_cast<std::size_t>(py) * b.paddedWidth + px;
        float v[kLargeInputChannels];
        for (int c = 0; c < 3; ++c) {
            const float col = b.color[3 * s + c];
            v[c] = toneMap(col);
            v[3 + c] = b.albedo ? b.albedo[3 * s + c] : 1.0f;
            v[6 + c] = b.normal ? normalToUnit(b.normal[3 * s + c]) : 0.5f;
            b.c[3 * d + c] = col;
            sumC[c] += col;
        }
        v[9] = b.depth ? depthToUnit(b.depth[s], ds) : 0.0f;
        std::uint32_t* dst = reinterpret_cast<std::uint32_t*>(b.x + d * kLargeInputStride);
        for (int w = 0; w < kLargeInputStride / 2; ++w) {
            const int c = 2 * w;
            dst[w] = packHalves(c < kLargeInputChannels ? v[c] : 0.0f,
                c + 1 < kLargeInputChannels ? v[c + 1] : 0.0f);
        }
        for (int c = 0; c < kLargeInputChannels; ++c)
            sum[c] += v[c];
    }
    const std::size_t h = static_cast<std::size_t>(yh) * (b.paddedWidth / 2) + xh;
    std::uint32_t* dst = reinterpret_cast<std::uint32_t*>(b.xHalf + h * kLargeInputStride);
    for (int w = 0; w < kLargeInputStride / 2; ++w) {
        const int c = 2 * w;
        dst[w] = packHalves(c < kLargeInputChannels ? sum[c] / 4.0f : 0.0f,
            c + 1 < kLargeInputChannels ? sum[c + 1] / 4.0f : 0.0f);
    }
    for (int c = 0; c < 3; ++c)
        b.cHalf[3 * h + c] = sumC[c] / 4.0f;
}

/// out(x, y) = D(in) at (x, y): the 2 x 2 window summed in row order, then / 4 (nn::down2);
/// `in` is (2 w) x (2 h) with `channels` floats per pixel.
AFN_HD void down2Pixel(const float* in, float* out, int w, int channels, int x, int y)
{
    const std::size_t wi = 2 * static_cast<std::size_t>(w);
    const float* a = in + (2 * y * wi + 2 * x) * channels;
    const float* b = a + channels;
    const float* c = a + wi * channels;
    const float* d = c + channels;
    float* o = out + (static_cast<std::size_t>(y) * w + x) * channels;
    for (int k = 0; k < channels; ++k)
        o[k] = (a[k] + b[k] + c[k] + d[k]) / 4.0f;
}

/// A logit that overflowed (+-Inf) becomes +-FLT_MAX and a NaN one the lowest value (the CPU's
/// finiteLogit, cpu/afn_fusion.cpp).
AFN_HD float finiteLogitDevice(float v)
{
    return v != v ? -3.402823466e38f : minOf(maxOf(v, -3.402823466e38f), 3.402823466e38f);
}

/// k = softmax(logits[0 .. n - 1]) as the CPU's softmax() (cpu/afn_fusion.cpp): finite logits,
/// the maximum subtracted, exp, the sum, times 1 / sum.
AFN_HD void softmaxOf(const float* logits, int n, float* k)
{
    for (int j = 0; j < n; ++j)
        k[j] = finiteLogitDevice(logits[j]);
    float m = k[0];
    for (int j = 1; j < n; ++j)
        m = maxOf(m, k[j]);
    float s = 0.0f;
    for (int j = 0; j < n; ++j) {
        k[j] = expf(k[j] - m);
        s += k[j];
    }
    const float inv = 1.0f / s;
    for (int j = 0; j < n; ++j)
        k[j] *= inv;
}

/// One scale's filtering: the head's logits (`logitStride` floats per pixel, taps first), the
/// scale's colour and the filtered output (3 floats per pixel each, width x height).
struct LargeFilterArgs {
    const float* logits = nullptr;
    int logitStride = 0;
    const float* color = nullptr;
    float* out = nullptr;
    int width = 0;
    int height = 0;
};

/// Pixel (x, y): softmax of the 25 logits (softmaxOf()), then sum over taps j = (dy + 2) * 5 + (dx
/// + 2) of k_j * colour(clamp(x + dx), clamp(y + dy)) in index order (network_large.cpp
/// filterScale()).
AFN_HD void largeFilterPixel(const LargeFilterArgs& a, int x, int y)
{
    const std::size_t p = static_cast<std::size_t>(y) * a.width + x;
    float k[kLargeTaps];
    softmaxOf(a.logits + p * a.logitStride, kLargeTaps, k);
    constexpr int r = kLargeKernelSize / 2;
    float acc[3] = { 0.0f, 0.0f, 0.0f };
    for (int j = 0; j < kLargeTaps; ++j) {
        const int sy = minOf(maxOf(y + j / kLargeKernelSize - r, 0), a.height - 1);
        const int sx = minOf(maxOf(x + j % kLargeKernelSize - r, 0), a.width - 1);
        const float* c = a.color + 3 * (static_cast<std::size_t>(sy) * a.width + sx);
        for (int ch = 0; ch < 3; ++ch)
            acc[ch] += k[j] * c[ch];
    }
    for (int ch = 0; ch < 3; ++ch)
        a.out[3 * p + ch] = acc[ch];
}

/// Eq. 3 between scales for the 2 x 2 block (cx, cy) of `fine` (width x height, 3 floats per
/// pixel; nn::fuseScales): fine = fine - a * D(fine) + a * coarse(cx, cy), a = sigmoid(logit
/// `channel` of `logits`, `logitStride` floats per fine pixel).
AFN_HD void fuseScalesBlock(float* fine, const float* coarse, const float* logits, int logitStride,
    int channel, int width, int cx, int cy)
{
    const std::size_t w = static_cast<std::size_t>(width);
    const float* p00 = fine + 3 * ((2 * cy) * w + 2 * cx);
    const float* p10 = p00 + 3;
    const float* p01 = p00 + 3 * w;
    const float* p11 = p01 + 3;
    float mean[3];
    for (int c = 0; c < 3; ++c)
        mean[c] = (p00[c] + p10[c] + p01[c] + p11[c]) / 4.0f;
    const float* lo = coarse + 3 * (static_cast<std::size_t>(cy) * (width / 2) + cx);
    for (int t = 0; t < 4; ++t) {
        const std::size_t p = (2 * cy + (t >> 1)) * w + 2 * cx + (t & 1);
        const float a = 1.0f / (1.0f + expf(-logits[p * logitStride + channel]));
        float* o = fine + 3 * p;
        for (int c = 0; c < 3; ++c)
            o[c] = o[c] - a * mean[c] + a * lo[c];
    }
}

/// A refinement module's input at padded pixel p: [T(o), albedo, normal01, depth01], the last
/// seven channels x's own halves (network_large.cpp refine()), zero up to the stride.
AFN_HD void largeRefineInputPixel(
    const float* o, const std::uint16_t* x, std::uint16_t* refineInput, std::size_t p)
{
    const std::uint16_t* xp = x + p * kLargeInputStride;
    std::uint16_t* r = refineInput + p * kLargeInputStride;
    for (int c = 0; c < 3; ++c)
        r[c] = toHalf(toneMap(o[3 * p + c]));
    for (int c = 3; c < kLargeInputStride; ++c)
        r[c] = c < kLargeInputChannels ? xp[c] : std::uint16_t(0);
}

} // namespace afn::cuda
