// SPDX-License-Identifier: Apache-2.0
// Device layers and tensors (see cuda/device_layers.h).
#include "cuda/device_layers.h"

#include "base/exception.h"

namespace afn::cuda {

void DeviceLayer::upload(const nn::Conv& conv, int upChannels, cudaStream_t stream)
{
    packed = packConv(conv, upChannels);
    weights.resize(packed.weights.size());
    bias.resize(packed.bias.size());
    AFN_CUDA_CHECK(cudaMemcpyAsync(
        weights.data(), packed.weights.data(), weights.bytes(), cudaMemcpyHostToDevice, stream));
    AFN_CUDA_CHECK(cudaMemcpyAsync(
        bias.data(), packed.bias.data(), bias.bytes(), cudaMemcpyHostToDevice, stream));
}

void HalfTensor::allocate(int w, int h, int channels, bool poison, cudaStream_t stream)
{
    width = w;
    height = h;
    stride = channelStride(channels);
    allocateBuffer(data, static_cast<std::size_t>(w) * h * stride, poison, stream);
}

ConvOperands convOperands(const DeviceLayer& layer, const HalfTensor* up, const HalfTensor& same)
{
    const PackedConv& pc = layer.packed;
    const bool upOk = up ? (pc.upChunks() * kChunk == up->stride && 2 * up->width == same.width
                          && 2 * up->height == same.height)
                         : pc.upChunks() == 0;
    if (!upOk || pc.sameChunks() * kChunk != same.stride || pc.tiles() == 0)
        throwInvalidOperation("CUDA afn: a layer does not match its input tensors");
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
    op.weights = layer.weights.data();
    op.bias = layer.bias.data();
    op.tiles = pc.tiles();
    return op;
}

} // namespace afn::cuda
