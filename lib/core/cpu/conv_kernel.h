// SPDX-License-Identifier: Apache-2.0
// The CPU kernel of nn::Conv: direct k x k convolution rows over interleaved (H, W, C) images,
// 4 output pixels x 8 output channels per micro-kernel step (register blocking).
#pragma once

#include "base/image.h"

namespace afn::cpu {

/// One convolution's operands (see nn::Conv::run for the meaning of `up` and `same`).
struct ConvArgs {
    const Image* up; ///< half-size input read through nearest 2x upsampling, or null
    const Image* same; ///< full-size input
    Image* out; ///< output, already sized
    const float* wp; ///< weights [ky][kx][ci][cp]
    const float* bp; ///< bias [cp]
    int in, k, cp, outC, nu, ns;
    bool relu;
};

/// Output rows [y0, y1).
void convRows(const ConvArgs& a, int y0, int y1);

} // namespace afn::cpu
