// SPDX-License-Identifier: Apache-2.0
// Device layers and tensors (see cuda/device_layers.h).
#include "cuda/device_layers.h"

#include "cuda/conv_operands.h"

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
    return convOperandsOf(layer.packed, layer.weights.data(), layer.bias.data(), up, same);
}

} // namespace afn::cuda
