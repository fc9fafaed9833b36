// SPDX-License-Identifier: Apache-2.0
// Host layers and tensors of the emulated pipelines (see emulated_tensors.h).
#include "emulated_tensors.h"

#include "base/exception.h"

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
    const PackedConv& pc = layer.packed;
    if ((up && (pc.upChunks() * kChunk != up->stride || 2 * up->width != same.width))
        || (!up && pc.upChunks() != 0) || pc.sameChunks() * kChunk != same.stride)
        afn::throwInvalidOperation("emulated CUDA afn: a layer does not match its inputs");
    ConvOperands op;
    op.up = up ? up->data.data() : nullptr;
    op.upStride = up ? up->stride : 0;
    op.upChunks = pc.upChunks();
    op.upWidth = up ? up->width : 0;
    op.same = same.data.data();
    op.sameStride = same.stride;
    op.sameChunks = pc.sameChunks();
    op.width = same.width;
    op.height = same.height;
    op.ksize = pc.ksize;
    op.weights = pc.weights.data();
    op.bias = pc.bias.data();
    op.tiles = pc.tiles();
    return op;
}

} // namespace afntest
