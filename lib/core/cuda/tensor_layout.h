// SPDX-License-Identifier: Apache-2.0
// Memory layouts of the CUDA AFN engine. Plain C++ (no CUDA header), built in every configuration
// so that the index math is tested on any machine (tests/unit/core/cuda/test_cuda_layout.cpp):
//   activations  NHWC half precision; the channel stride is rounded up to 16 (one K step of the
//                tensor-core instruction mma.m16n8k16); channels past a tensor's own count hold 0.
//   conv weights for each tap, 16-channel K chunk and output channel n: 8 32-bit words, word w
//                holding the halves of the chunk's input channels 2w (low 16 bits) and 2w + 1;
//                output channels rounded up to 8 (one N tile); zero wherever padded. A tap's K
//                chunks are the chunks of the `up` input, then those of the `same` input (the
//                order of nn::Conv::run's concat(U(up), same)).
//   frame        the network runs on the frame padded to a multiple of 8 (methods/afn/network.h);
//                level l of the U-Net has the padded size divided by 2^l.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace afn::nn {
class Conv;
}

namespace afn::cuda {

constexpr int kChunk = 16; ///< input channels per K step
constexpr int kTileN = 8; ///< output channels per N tile
constexpr int kPadMultiple = 8; ///< the frame is padded to a multiple of this (3 pooling levels)

/// Channel stride (halves per pixel) of an activation tensor with `channels` channels.
constexpr int channelStride(int channels)
{
    return (channels + kChunk - 1) / kChunk * kChunk;
}
/// Number of 16-channel K chunks that hold `channels` channels.
constexpr int chunkCount(int channels)
{
    return channelStride(channels) / kChunk;
}
/// Number of 8-channel N tiles that hold `channels` output channels.
constexpr int tileCount(int channels)
{
    return (channels + kTileN - 1) / kTileN;
}
/// `n` rounded up to a multiple of kPadMultiple.
constexpr int paddedSize(int n)
{
    return (n + kPadMultiple - 1) / kPadMultiple * kPadMultiple;
}

/// Index of weight word `w` (channels 2w and 2w + 1 of K chunk `kc`) of output channel `n` at
/// `tap`, in a layer with `kChunks` chunks per tap and `tiles` N tiles.
constexpr std::size_t packedWeightIndex(int tap, int kc, int n, int w, int kChunks, int tiles)
{
    return ((static_cast<std::size_t>(tap) * kChunks + kc)
                   * (static_cast<std::size_t>(tiles) * kTileN)
               + n)
        * 8
        + w;
}

/// IEEE 754 binary16 from a float, rounded to nearest even (as CUDA's __float2half_rn).
std::uint16_t floatToHalf(float v);
/// The float value of an IEEE 754 binary16.
float halfToFloat(std::uint16_t h);

/// A convolution layer in the tensor-core kernels' layout.
struct PackedConv {
    int ksize = 0; ///< 1 or 3
    int upChannels = 0; ///< input channels read from the half-size input (0: none)
    int sameChannels = 0; ///< input channels read from the same-size input
    int outChannels = 0;
    std::vector<std::uint32_t> weights; ///< packedWeightIndex() order
    std::vector<float> bias; ///< tiles() * kTileN values, zero where padded

    int upChunks() const { return chunkCount(upChannels); }
    int sameChunks() const { return chunkCount(sameChannels); }
    int kChunks() const { return upChunks() + sameChunks(); }
    int tiles() const { return tileCount(outChannels); }
};

/// Pack a loaded layer whose input is concat(U(up), same), `upChannels` of its input channels
/// coming from `up` (0 for a plain convolution).
PackedConv packConv(const nn::Conv& conv, int upChannels);

/// The albedo trust's head (3x3, 1 output) as albedo_trust_block.h reads it, in float: for each
/// tap (ky * 3 + kx) its input channels' weights, then the bias.
std::vector<float> packTrustHead(const nn::Conv& conv);

} // namespace afn::cuda
