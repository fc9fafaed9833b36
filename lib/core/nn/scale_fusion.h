// SPDX-License-Identifier: Apache-2.0
// Fusion of two scales of a filtered image (Lee et al.'s Eq. 3 between scales, the same as
// Vogels et al.'s MR-KP scale composition): the fine scale keeps its own high frequencies and
// takes its low frequencies, by a per-pixel weight, from the coarser scale:
//   fine = fine - a * U(D(fine)) + a * U(coarse),   a = sigmoid(logits channel `channel`)
// with D = 2x2 average pooling (PyTorch avg_pool2d: the four pixels summed in row order, then
// divided by 4) and U = nearest 2x upsampling. Used by MR-KP (methods/mrkp) and AFN large
// (methods/afn/network_large.h).
#pragma once

#include "base/image.h"

namespace afn::nn {

/// In place on `fine` (3 ch, even size); `coarse` (3 ch) has half its size; `logits` has fine's
/// size and the weight's logit in channel `channel`. Throws InvalidArgument on other sizes.
void fuseScales(Image& fine, const Image& coarse, const Image& logits, int channel);

} // namespace afn::nn
