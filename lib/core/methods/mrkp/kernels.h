// SPDX-License-Identifier: Apache-2.0
// MR-KP's filtering and level blending (training/afn/baselines/mrkp.py apply_kernel, forward):
//   f_l(p) = sum_j relu(k_j(p)) d_l(p + o_j) / (sum_j relu(k_j(p)) + 1e-8)
// 5x5 taps, tap j = (dy + 2) * 5 + (dx + 2), the image read with edge replication outside;
//   o_2 = f_2;  o_l = f_l - a_l * U(D(f_l)) + a_l * U(o_{l+1}),  a_l = sigmoid(head_l[25])
// with D = 2x2 average pooling and U = nearest 2x upsampling.
#pragma once

#include "base/image.h"

namespace afn::mrkp {

constexpr int kKernelSize = 5;
constexpr int kTaps = kKernelSize * kKernelSize;
constexpr int kHeadChannels = kTaps + 1;

/// f = the kernels of `head` (W x H x 26) applied to `color` (W x H x 3).
void applyKernels(const Image& color, const Image& head, Image& filtered);

/// In place: fine = fine - a * U(D(fine)) + a * U(coarse), a = sigmoid(head channel 25);
/// coarse has half fine's size.
void blendLevels(Image& fine, const Image& coarse, const Image& head);

} // namespace afn::mrkp
