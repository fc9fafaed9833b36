// SPDX-License-Identifier: Apache-2.0
// One warp's share of a convolution on tensor cores: which input halves each lane loads into its A
// and B registers, and where each lane's accumulators go. A warp computes 16 output pixels (the M
// rows of mma.m16n8k16) for some N tiles of 8 output channels; K runs over the taps and the
// 16-channel chunks of concat(U(up), same) (nn::Conv::run's input). Zero padding: input pixels
// outside the layer's frame read 0.
// The tile's 16 pixels are either 16 consecutive pixels of one row (Row16) or an 8 x 2 block
// (Block8x2: rows 0-7 of the tile on image row y, rows 8-15 on row y + 1), the shape the fused
// filtering kernel needs for its 2 x 2 pooling blocks.
#pragma once

#include "cuda/albedo_trust_block.h"
#include "cuda/fragment.h"

namespace afn::cuda {

/// Operands of one convolution (sizes in pixels, strides in halves per pixel).
struct ConvOperands {
    const std::uint16_t* up = nullptr; ///< half-size input read through nearest 2x upsampling
    int upStride = 0;
    int upChunks = 0; ///< K chunks read from `up` (0: no such input)
    int upWidth = 0; ///< width of `up` (width / 2)
    const std::uint16_t* same = nullptr; ///< same-size input
    int sameStride = 0;
    int sameChunks = 0;
    int width = 0; ///< the layer's frame (= output size = size of `same`)
    int height = 0;
    int ksize = 0; ///< 1 or 3
    const std::uint32_t* weights = nullptr; ///< PackedConv::weights on the device
    const float* bias = nullptr; ///< PackedConv::bias
    int tiles = 0; ///< N tiles (output channels / 8, rounded up)
    AFN_HD int kChunks() const { return upChunks + sameChunks; }
};

enum class TileShape { Row16, Block8x2 };

/// Image pixel of tile row `row` (0..15) for a tile whose first pixel is (x0, y0).
AFN_HD void tilePixel(TileShape shape, int x0, int y0, int row, int& x, int& y)
{
    if (shape == TileShape::Row16) {
        x = x0 + row;
        y = y0;
    } else {
        x = x0 + (row & 7);
        y = y0 + (row >> 3);
    }
}

/// A registers of `lane` for tap `tap` (ky * ksize + kx) and K chunk `kc`.
AFN_HD void loadConvA(const ConvOperands& op, TileShape shape, int lane, int x0, int y0, int tap,
    int kc, std::uint32_t (&a)[4])
{
    const int r = op.ksize / 2;
    const int dy = tap / op.ksize - r, dx = tap % op.ksize - r;
    for (int reg = 0; reg < 4; ++reg) {
        int px, py;
        tilePixel(shape, x0, y0, Fragment::aRow(lane, reg), px, py);
        px += dx;
        py += dy;
        if (px < 0 || py < 0 || px >= op.width || py >= op.height) {
            a[reg] = 0u;
            continue;
        }
        const std::uint16_t* p;
        if (kc < op.upChunks)
            p = op.up + (static_cast<std::size_t>(py >> 1) * op.upWidth + (px >> 1)) * op.upStride
                + kc * kChunk;
        else
            p = op.same + (static_cast<std::size_t>(py) * op.width + px) * op.sameStride
                + (kc - op.upChunks) * kChunk;
        a[reg] = loadWord(reinterpret_cast<const std::uint32_t*>(p + Fragment::aCol(lane, reg)));
    }
}

/// B registers of `lane` for tap `tap`, K chunk `kc` and N tile `tile`.
AFN_HD void loadConvB(
    const ConvOperands& op, int lane, int tap, int kc, int tile, std::uint32_t (&b)[2])
{
    const int n = tile * kTileN + Fragment::bCol(lane);
    for (int reg = 0; reg < 2; ++reg)
        b[reg] = loadWord(op.weights
            + packedWeightIndex(tap, kc, n, Fragment::bRow(lane, reg) / 2, op.kChunks(), op.tiles));
}

/// Output of a hidden layer: ReLU, half precision, NHWC with `stride` halves per pixel.
struct ReluOutput {
    std::uint16_t* data = nullptr;
    int stride = 0; ///< channelStride(output channels)
};

/// Write `lane`'s accumulators of N tile `tile` (bias added, ReLU) for a Row16 tile at (x0, y).
AFN_HD void storeRelu(const ConvOperands& op, const ReluOutput& out, int lane, int x0, int y,
    int tile, const float (&c)[4])
{
    for (int i = 0; i < 4; i += 2) {
        const int px = x0 + Fragment::cRow(lane, i);
        if (px >= op.width)
            continue;
        const int n = tile * kTileN + Fragment::cCol(lane, i);
        const float v0 = maxOf(c[i] + loadFloat(op.bias + n), 0.0f);
        const float v1 = maxOf(c[i + 1] + loadFloat(op.bias + n + 1), 0.0f);
        std::uint16_t* p
            = out.data + (static_cast<std::size_t>(y) * op.width + px) * out.stride + n;
        *reinterpret_cast<std::uint32_t*>(p) = packHalves(v0, v1);
    }
}

/// Output of a layer without activation in float (AFN large's heads): `channels` floats per
/// pixel (the layer's output channels), NHWC.
struct LinearOutput {
    float* data = nullptr;
    int channels = 0;
};

/// Write `lane`'s accumulators of N tile `tile` (bias added) for a Row16 tile at (x0, y).
AFN_HD void storeLinear(const ConvOperands& op, const LinearOutput& out, int lane, int x0, int y,
    int tile, const float (&c)[4])
{
    for (int i = 0; i < 4; ++i) {
        const int px = x0 + Fragment::cRow(lane, i), n = tile * kTileN + Fragment::cCol(lane, i);
        if (px >= op.width || n >= out.channels)
            continue;
        out.data[(static_cast<std::size_t>(y) * op.width + px) * out.channels + n]
            = c[i] + loadFloat(op.bias + n);
    }
}

/// Zero the channels between the last N tile and the stride (a 24-channel layer has a stride of
/// 32: channels 24-31 are written 0 so that the next layer may read them).
AFN_HD void storeZeroPadding(const ConvOperands& op, const ReluOutput& out, int lane, int x0, int y)
{
    for (int i = 0; i < 4; i += 2) {
        const int px = x0 + Fragment::cRow(lane, i);
        if (px >= op.width)
            continue;
        std::uint16_t* p = out.data + (static_cast<std::size_t>(y) * op.width + px) * out.stride;
        for (int n = op.tiles * kTileN + Fragment::cCol(lane, i); n < out.stride; n += kTileN)
            *reinterpret_cast<std::uint32_t*>(p + n) = 0u;
    }
}

/// Output of the last refinement layer: o = fused + conv (3 channels), back from the albedo
/// trust's space, remodulated by the albedo and cropped to the frame (methods/afn/network.cpp
/// refine() and crop(), albedo_trust.h, demodulate.h).
struct FinalOutput {
    const float* fused = nullptr; ///< padded frame, 3 floats per pixel
    const float* albedo = nullptr; ///< frame size, 3 floats per pixel; null: factor 1
    int plainAlbedo = 0; ///< 1: colour came demodulated (multiply by the plain albedo)
    /// The albedo trust's t (albedo_trust_block.h), half the padded frame, `trustWidth` floats per
    /// row; null: weights without the albedo trust
    const float* trust = nullptr;
    int trustWidth = 0;
    /// Work skipping (methods/afn/work_rows.h): per frame row, 0 where the row takes the cheap
    /// path, `cheap` (the TA colour the network filters, frame size, 3 floats per pixel,
    /// remodulated as the network's output) instead of the network's; null: every row computed
    const unsigned char* computedRows = nullptr;
    const float* cheap = nullptr;
    /// 1: `data` gets o itself after the albedo trust's division, neither clamped nor remodulated
    /// (a pass of the quality tier high, high_tier_pixel.h)
    int demodulated = 0;
    float* data = nullptr; ///< frame size, 3 floats per pixel
    int width = 0; ///< the frame (unpadded)
    int height = 0;
};

/// The output value of channel c at frame pixel (x, y) from the network's o: divided by the
/// albedo trust's s (methods/afn/albedo_trust.cpp undoAlbedoTrustRows(); a = the albedo of x, 1
/// without albedo), then remodulated (stages/demodulate.cpp remodulate()); on a skipped row the
/// cheap path's colour instead (Network::run: copied as it is, then remodulated).
AFN_HD float outputValue(const FinalOutput& out, int x, int y, int c, float o)
{
    const std::size_t pixel = static_cast<std::size_t>(y) * out.width + x;
    const float albedo = out.albedo ? loadFloat(out.albedo + 3 * pixel + c) : 1.0f;
    if (out.computedRows && !out.computedRows[y])
        o = loadFloat(out.cheap + 3 * pixel + c);
    else if (out.trust)
        o /= trustScale(albedo,
            loadFloat(out.trust + static_cast<std::size_t>(y / 2) * out.trustWidth + x / 2));
    if (out.demodulated)
        return o;
    const float a = out.albedo ? albedoFactor(albedo, out.plainAlbedo != 0) : 1.0f;
    return clampIrradiance(o) * a;
}

/// Write `lane`'s accumulators of the 3-channel layer (N tile 0) for a Row16 tile at (x0, y).
AFN_HD void storeFinal(
    const ConvOperands& op, const FinalOutput& out, int lane, int x0, int y, const float (&c)[4])
{
    if (y >= out.height)
        return;
    for (int i = 0; i < 4; ++i) {
        const int px = x0 + Fragment::cRow(lane, i), ch = Fragment::cCol(lane, i);
        if (ch >= 3 || px >= out.width)
            continue;
        const float r = c[i] + loadFloat(op.bias + ch);
        const float o
            = loadFloat(out.fused + (static_cast<std::size_t>(y) * op.width + px) * 3 + ch) + r;
        out.data[3 * static_cast<std::size_t>(y) * out.width + 3 * px + ch]
            = outputValue(out, px, y, ch, o);
    }
}

} // namespace afn::cuda
