// SPDX-License-Identifier: Apache-2.0
// Per-thread code of AFN's optional quarter-resolution scale on the CUDA engine
// (methods/afn/quarter_scale.cpp), run after filtering and fusion on the fused image i:
//   quarterDeltaPixel      at 1/4 of the padded size: softmax over head4's 49 logits, the 7x7
//                          kernel on l = D(D(i)) (taps outside read 0, not renormalised, as
//                          applyKernel()), delta = sigmoid(beta) * (K * l - l)
//   addUpsampled4Pixel     i += U4(delta), PyTorch's bilinear rule (align_corners=False)
// and what the network does with i afterwards where the fused kernel did it before:
//   refineInputPixel       the refinement input [T(i), x's albedo, normal01, depth01]
//   fusedOutputPixel       the output without refinement (outputValue of i)
// D is down2Pixel (large_pixel.h), head4 a 1x1 convolution with float logits (convLinear).
// Compiled with --fmad=false like the CPU's arithmetic.
#pragma once

#include "cuda/conv_tile.h"
#include "cuda/filter_fuse_lane.h"
#include "cuda/large_pixel.h"

#include <cstddef>

namespace afn::cuda {

constexpr int kQuarterTaps = 49; ///< 7x7 (methods/afn/fusion.h kKernelTaps)
constexpr int kQuarterKernelSize = 7;

/// The quarter scale's buffers (1/4 of the padded size: width x height).
struct QuarterArgs {
    const float* logits = nullptr; ///< head4's output, `logitStride` floats per pixel
    int logitStride = 0;
    const float* low = nullptr; ///< l = D(D(i)), 3 floats per pixel
    float* delta = nullptr; ///< 3 floats per pixel
    int width = 0;
    int height = 0;
};

/// delta at quarter pixel (x, y); the softmax as the CPU's (softmaxOf()), the taps summed in row
/// order (applyKernel()).
AFN_HD void quarterDeltaPixel(const QuarterArgs& a, int x, int y)
{
    const std::size_t p = static_cast<std::size_t>(y) * a.width + x;
    const float* q = a.logits + p * a.logitStride;
    float k[kQuarterTaps];
    softmaxOf(q, kQuarterTaps, k);
    constexpr int r = kQuarterKernelSize / 2;
    float acc[3] = { 0.0f, 0.0f, 0.0f };
    for (int dy = 0; dy < kQuarterKernelSize; ++dy) {
        const int yy = y + dy - r;
        if (yy < 0 || yy >= a.height)
            continue;
        for (int dx = 0; dx < kQuarterKernelSize; ++dx) {
            const int xx = x + dx - r;
            if (xx < 0 || xx >= a.width)
                continue;
            const float* c = a.low + 3 * (static_cast<std::size_t>(yy) * a.width + xx);
            const float kv = k[dy * kQuarterKernelSize + dx];
            for (int ch = 0; ch < 3; ++ch)
                acc[ch] += kv * c[ch];
        }
    }
    const float beta = 1.0f / (1.0f + expf(-q[kQuarterTaps]));
    const float* l = a.low + 3 * p;
    for (int ch = 0; ch < 3; ++ch)
        a.delta[3 * p + ch] = beta * (acc[ch] - l[ch]);
}

/// One tap pair of the 4x bilinear upsampling along an axis (quarter_scale.cpp sourceTaps()).
struct Upsample4Taps {
    int i0, i1;
    float l1;
};
AFN_HD Upsample4Taps upsample4Taps(int dst, int srcSize)
{
    float s = 0.25f * (static_cast<float>(dst) + 0.5f) - 0.5f;
    s = maxOf(s, 0.0f);
    const int i0 = static_cast<int>(s) < srcSize - 1 ? static_cast<int>(s) : srcSize - 1;
    const int i1 = i0 + (i0 < srcSize - 1 ? 1 : 0);
    return { i0, i1, s - static_cast<float>(i0) };
}

/// fused(x, y) += U4(delta)(x, y); `fused` is width x height, `delta` a quarter of it.
AFN_HD void addUpsampled4Pixel(
    const float* delta, float* fused, int width, int height, int x, int y)
{
    const int ws = width / 4, hs = height / 4;
    const Upsample4Taps ty = upsample4Taps(y, hs), tx = upsample4Taps(x, ws);
    const float h1 = ty.l1, h0 = 1.0f - h1, w1 = tx.l1, w0 = 1.0f - w1;
    auto at = [&](int sx, int sy) { return delta + 3 * (static_cast<std::size_t>(sy) * ws + sx); };
    const float *a = at(tx.i0, ty.i0), *b = at(tx.i1, ty.i0);
    const float *c = at(tx.i0, ty.i1), *d = at(tx.i1, ty.i1);
    float* o = fused + 3 * (static_cast<std::size_t>(y) * width + x);
    for (int ch = 0; ch < 3; ++ch)
        o[ch] += h0 * (w0 * a[ch] + w1 * b[ch]) + h1 * (w0 * c[ch] + w1 * d[ch]);
}

/// The refinement input of padded pixel p from the fused image (the fused kernel's
/// refineInputChannel()).
AFN_HD void refineInputPixel(
    const float* fused, const std::uint16_t* x, std::uint16_t* refineInput, std::size_t p)
{
    const float f[3] = { fused[3 * p], fused[3 * p + 1], fused[3 * p + 2] };
    for (int c = 0; c < kInputStride; ++c)
        refineInput[p * kInputStride + c] = refineInputChannel(c, f, x + p * kInputStride);
}

/// The output at frame pixel (x, y) from the fused image (padded width `paddedWidth`) without a
/// refinement: outputValue(), as the fused kernel writes it.
AFN_HD void fusedOutputPixel(
    const float* fused, int paddedWidth, const FinalOutput& out, int x, int y)
{
    const std::size_t p = static_cast<std::size_t>(y) * out.width + x;
    const std::size_t q = static_cast<std::size_t>(y) * paddedWidth + x;
    for (int c = 0; c < 3; ++c)
        out.data[3 * p + c] = outputValue(out, x, y, c, fused[3 * q + c]);
}

} // namespace afn::cuda
