// SPDX-License-Identifier: Apache-2.0
// The device side of a network's layers and activations, shared by AFN's graph (afn_pipeline.h)
// and AFN large's (large_graph.h): a packed convolution layer uploaded to the GPU, a
// half-precision NHWC tensor, the operands of a convolution over them, and the allocation rule of
// every device buffer (poisoned with NaN on request).
#pragma once

#include "cuda/check.h"
#include "cuda/conv_tile.h"
#include "cuda/device_memory.h"
#include "cuda/tensor_layout.h"
#include "nn/conv.h"

#include <cstddef>
#include <cstdint>

namespace afn::cuda {

/// Pixels of a w x h image (std::size_t: frames past 2^31 values stay countable).
inline std::size_t pixelCount(int w, int h)
{
    return static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
}

/// Allocate `count` elements (nothing when the size is unchanged); a fresh allocation is filled
/// with 0xff bytes (NaN as float and as half) on `stream` when `poison` is set. (Every copy and
/// fill goes through the pipeline's own stream: the legacy default stream is not ordered with a
/// non-blocking stream.)
template <typename T>
void allocateBuffer(DeviceBuffer<T>& b, std::size_t count, bool poison, cudaStream_t stream)
{
    if (b.size() == count)
        return;
    b.resize(count);
    if (poison && count > 0)
        AFN_CUDA_CHECK(cudaMemsetAsync(b.data(), 0xff, b.bytes(), stream));
}

/// A convolution layer packed for the tensor cores (tensor_layout.h) and its weights and bias on
/// the GPU.
struct DeviceLayer {
    PackedConv packed;
    DeviceBuffer<std::uint32_t> weights;
    DeviceBuffer<float> bias;
    /// Pack `conv` (its input concat(U(up), same) with `upChannels` from `up`) and copy it to the
    /// GPU on `stream` (the caller synchronises before the host copy goes away: packed is kept).
    void upload(const nn::Conv& conv, int upChannels, cudaStream_t stream);
};

/// A half-precision NHWC activation tensor, `stride` = channelStride(channels) halves per pixel.
struct HalfTensor {
    DeviceBuffer<std::uint16_t> data;
    int width = 0, height = 0, stride = 0;
    void allocate(int w, int h, int channels, bool poison, cudaStream_t stream);
};

/// The operands of `layer` over concat(U(up), same) (`up` null: a plain convolution); throws
/// InvalidOperation when the layer does not match the tensors.
ConvOperands convOperands(const DeviceLayer& layer, const HalfTensor* up, const HalfTensor& same);

} // namespace afn::cuda
