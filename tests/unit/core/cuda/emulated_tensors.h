// SPDX-License-Identifier: Apache-2.0
// Host counterparts of cuda/device_layers.h for the emulated pipelines: a packed layer, a
// half-precision NHWC tensor (allocated as NaN halves, so a value no kernel wrote shows up) and the
// operands of a convolution over them.
#pragma once

#include "base/image.h"
#include "cuda/conv_tile.h"
#include "cuda/tensor_layout.h"

#include <cstdint>
#include <vector>

namespace afntest {

struct HostLayer {
    afn::cuda::PackedConv packed;
};

struct HostTensor {
    std::vector<std::uint16_t> data;
    int width = 0, height = 0, stride = 0;
    void allocate(int w, int h, int channels);
    afn::Image toImage(int channels) const;
};

/// cuda::convOperandsOf over host buffers; throws InvalidOperation when they do not match.
afn::cuda::ConvOperands hostOperands(
    const HostLayer& layer, const HostTensor* up, const HostTensor& same);

} // namespace afntest
