// SPDX-License-Identifier: Apache-2.0
// The operands of a convolution over concat(U(up), same) from a packed layer and its tensors, for
// the device's tensors (device_layers.h) and the host emulation's alike: any tensor type with
// `data.data()` (halves), `width`, `height` and `stride`. Host code only (plain C++).
#pragma once

#include "base/exception.h"
#include "cuda/conv_tile.h"
#include "cuda/tensor_layout.h"

#include <cstdint>

namespace afn::cuda {

/// `weights` and `bias` are the layer's packed values where the kernels read them (device or
/// host memory); `up` null: a plain convolution. Throws InvalidOperation when the layer does not
/// match the tensors.
template <typename Tensor>
ConvOperands convOperandsOf(const PackedConv& pc, const std::uint32_t* weights, const float* bias,
    const Tensor* up, const Tensor& same)
{
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
    op.weights = weights;
    op.bias = bias;
    op.tiles = pc.tiles();
    return op;
}

} // namespace afn::cuda
