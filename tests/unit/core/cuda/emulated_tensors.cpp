// SPDX-License-Identifier: Apache-2.0
// Host layers and tensors of the emulated pipelines (see emulated_tensors.h).
#include "emulated_tensors.h"

#include "cuda/conv_operands.h"

namespace afntest {

using namespace afn::cuda;

void HostTensor::allocate(int w, int h, int channels)
{
    width = w;
    height = h;
    stride = channelStride(channels);
    // NaN halves: a value the kernels never wrote shows up in the results.
    data.assign(static_cast<std::size_t>(w) * h * stride, 0xffffu);
}

afn::Image HostTensor::toImage(int channels) const
{
    afn::Image img(width, height, channels);
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p)
        for (int c = 0; c < channels; ++c)
            img.data()[p * channels + c] = halfToFloat(data[p * stride + c]);
    return img;
}

ConvOperands hostOperands(const HostLayer& layer, const HostTensor* up, const HostTensor& same)
{
    return convOperandsOf(
        layer.packed, layer.packed.weights.data(), layer.packed.bias.data(), up, same);
}

} // namespace afntest
