// SPDX-License-Identifier: Apache-2.0
// AFN filtering and fusion (Lee et al., Eq. 2 and 3) as one fused pass per 2x2 pixel block:
// the 1x1 kernel heads, the softmax over 49 taps, the 7x7 filtering of the HDR images and the
// fusion run per pixel, so neither the kernel maps nor the unfolded 49-channel image stack is
// ever stored.
//   K_1spp = softmax(head1(d1))            half resolution, applied to D(r_1spp) -> d_1spp
//   [K_TA, a] = headTA(concat(U(d1), x))   full resolution, K_TA applied to r_TA -> d_TA
//   alpha = sigmoid(a)
//   i = d_TA - alpha * U(D(d_TA)) + alpha * U(d_1spp)                        (Eq. 3)
// Tap j = (dy + 3) * 7 + (dx + 3) reads the image at (x + dx, y + dy); taps outside the image
// read 0 and the kernel is not renormalised (PyTorch F.unfold with zero padding).
#pragma once

#include "base/image.h"
#include "nn/conv.h"

namespace afn::afnet {

/// Kernel size k of the AFN kernels (7x7 = 49 taps).
constexpr int kKernelSize = 7;
constexpr int kKernelTaps = kKernelSize * kKernelSize;

/// Inputs of the fused pass; every full-resolution image has the same even size.
struct FusionInputs {
    const Image* d1 = nullptr; ///< half-res decoder features
    const Image* x = nullptr; ///< full-res network input (13 or 14 ch)
    const Image* colorTa = nullptr; ///< full-res TA colour, demodulated HDR (3 ch)
    const Image* color1Half = nullptr; ///< D(1-spp colour), half res (3 ch)
    const nn::Conv* head1 = nullptr; ///< 1x1, d1 -> 49
    const nn::Conv* headTa = nullptr; ///< 1x1, d1 + x -> 50
};

/// Outputs: fused image i, d_TA, alpha (full res), d_1spp (half res); all but `fused` may be null
/// for filterAndFuseRows (not kept).
struct FusionOutputs {
    Image* fused = nullptr;
    Image* filteredTa = nullptr;
    Image* alpha = nullptr;
    Image* filtered1Half = nullptr;
};

/// Run heads, softmax, filtering and fusion over the whole frame (outputs resized here).
void filterAndFuse(const FusionInputs& in, const FusionOutputs& out);

/// The same for half-resolution rows [y0, y1) (full rows [2 y0, 2 y1)) on the calling thread,
/// into outputs already of their size. The images may be a window of the frame (network
/// stripes): rows outside them read zero, which is right only at the frame's border, so a window
/// must hold the 3-pixel filter halo (and d1, x the same rows) wherever it is not at the border.
void filterAndFuseRows(const FusionInputs& in, const FusionOutputs& out, int y0, int y1);

/// Softmax over `n` logits in place, with the maximum subtracted first.
void softmax(float* v, int n);

/// Apply normalised 7x7 kernel `k` (49 weights) at (x, y) of a 3-channel image; writes rgb.
void applyKernel(const Image& img, int x, int y, const float* k, float* rgb);

} // namespace afn::afnet
