// SPDX-License-Identifier: Apache-2.0
// Pooling and activation helpers of the learned baselines (ONND, MR-KP). The 2x2 average pooling
// is nn::down2 (conv.h).
#pragma once

#include "base/image.h"

namespace afn::nn {

/// 2x2 max pooling of an image with even size into `out` (half size), as PyTorch max_pool2d(2).
void maxPool2(const Image& in, Image& out);

/// x = x > 0 ? x : slope * x, in place (PyTorch leaky_relu).
void leakyRelu(Image& img, float slope);

/// Copy every channel of `src` into channels [offset, offset + src.channels()) of `dst` (same
/// width and height): the second half of a channel concatenation.
void copyChannels(const Image& src, Image& dst, int offset);

} // namespace afn::nn
