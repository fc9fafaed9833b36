// SPDX-License-Identifier: Apache-2.0
// MR-KP's filtering (training/afn/baselines/mrkp.py apply_kernel):
//   f_l(p) = sum_j relu(k_j(p)) d_l(p + o_j) / (sum_j relu(k_j(p)) + 1e-8)
// 5x5 taps, tap j = (dy + 2) * 5 + (dx + 2), the image read with edge replication outside.
// The level blending o_2 = f_2;  o_l = f_l - a_l * U(D(f_l)) + a_l * U(o_{l+1}),
// a_l = sigmoid(head_l[25]), is nn::fuseScales (nn/scale_fusion.h), shared with AFN large.
#pragma once

#include "base/image.h"

namespace afn::mrkp {

constexpr int kKernelSize = 5;
constexpr int kTaps = kKernelSize * kKernelSize;
constexpr int kHeadChannels = kTaps + 1;

/// f = the kernels of `head` (W x H x 26) applied to `color` (W x H x 3).
void applyKernels(const Image& color, const Image& head, Image& filtered);

} // namespace afn::mrkp
