// SPDX-License-Identifier: Apache-2.0
// AFN's optional quarter-resolution scale (training/afn/model.py, `quarter`), run after
// filtering and fusion on the fused image i:
//   [K_q logits, beta logit] = head4(d2)            1x1, d2 -> 50, at 1/4 of the padded size
//   l = D(D(i)),  i <- i + U4(sigmoid(beta) * (K_q * l - l))
// with K_q the softmax over the 49 taps of a 7x7 kernel (taps outside read 0, not renormalised,
// as fusion.h), D 2x2 average pooling and U4 bilinear 4x upsampling with PyTorch's
// align_corners=False rule (source (x + 0.5) / 4 - 0.5, clamped at 0; the far neighbour clamped
// to the last pixel). It widens the filter's footprint from 14 to 28 full-resolution pixels.
// Whole-frame only: models with it run through Network::runWholeFrame (network.h).
#pragma once

#include "base/image.h"
#include "nn/conv.h"

namespace afn::afnet {

/// Buffers of the quarter scale, reused across frames of one size.
struct QuarterBuffers {
    Image half, low, logits, delta; ///< D(i), l = D(D(i)), head4 output, beta * (K_q * l - l)
};

/// Apply the quarter scale to `fused` (3 ch, padded size, a multiple of 4) in place; `d2` is the
/// decoder's quarter-resolution output, `head4` the 1x1 head (d2 channels -> 50). Keeps the
/// intermediates in `buf`.
void applyQuarterScale(const nn::Conv& head4, const Image& d2, Image& fused, QuarterBuffers& buf);

/// U4: `dst` (W x H, 3 ch) += the bilinear 4x upsampling of `src` (W/4 x H/4, 3 ch).
void addUpsampled4(const Image& src, Image& dst);

} // namespace afn::afnet
