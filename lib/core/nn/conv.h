// SPDX-License-Identifier: Apache-2.0
// Convolution layers of the AFN engine: direct (im2col-free) k x k convolutions, stride 1, zero
// padding k/2, on interleaved (H, W, C) images, with oneTBB over rows. Two kernel families, chosen
// at run time (cpu/isa.h): AVX-512 micro-kernels (cpu/conv_avx512.cpp: zero-padded input band,
// up to 14 pixels x 64 channels of register blocking, weights [tap][in][out padded to 16]) where
// the CPU has AVX-512F, else the portable kernel (cpu/conv_kernel.cpp: 4 pixels x 8 channels,
// weights [tap][in][out padded to 8], cloned for x86-64-v3 and baseline).
#pragma once

#include "base/image.h"
#include "cpu/conv_kernel.h"
#include "nn/weights.h"

#include <string>
#include <vector>

namespace afn::nn {

/// Most output channels of one layer (the 7x7 kernel head has 50).
constexpr int kMaxChannels = 256;

/// Arithmetic of a layer on the AVX-512 engine: fp32, or bfloat16 operands with fp32 sums
/// (cpu/conv_avx512_bf16.cpp). The portable kernels always run fp32.
enum class Precision { Fp32, Bf16 };

/// One conv layer: PyTorch Conv2d(Cin, Cout, k, padding=k/2) with bias.
class Conv {
public:
    /// Load "<name>.weight" (Cout, Cin, k, k) and "<name>.bias" (Cout). Throws "invalid or
    /// corrupted weights" if the shapes are inconsistent, k is not 1, 3 or 5, Cin differs from
    /// `expectedIn`, or Cout from `expectedOut` (when >= 0). Both kernel families take k as a
    /// run-time value (the taps loop and the band's k/2-pixel halo), so 5x5 (WSKPN, NBGD) runs on
    /// the same kernels as 1x1 and 3x3; tests/unit/core/nn/test_conv5.cpp checks it on both.
    void load(
        const WeightsArchive& a, const std::string& name, int expectedIn, int expectedOut = -1);

    int inChannels() const { return m_in; }
    int outChannels() const { return m_out; }
    int kernelSize() const { return m_k; }
    bool loaded() const { return m_out > 0; }

    /// out = conv(concat(U(up), same)), optionally followed by ReLU. Channels [0, up.channels)
    /// of the input read `up` (half of out's size, nearest 2x upsampling, never materialised),
    /// the others read `same` (out's size). `up` may be null. `out` is resized to same's size.
    void run(const Image* up, const Image& same, Image& out, bool relu) const;

    /// Rows [y0, y1) of the same convolution on the calling thread, for callers that keep only a
    /// few rows (the fused AFN heads, the refinement strips): row y at dst + (y - y0) * rowStride,
    /// pixels pixelStride (>= outChannels()) floats apart. Only output columns [x0, x1) when
    /// given (x1 < 0: to the width), column x0 at dst: the AFN heads run in column chunks whose
    /// logits stay in cache; every output is the same with or without chunks.
    void runRows(const Image* up, const Image& same, int y0, int y1, float* dst, long rowStride,
        int pixelStride, bool relu, int x0 = 0, int x1 = -1) const;

    /// Run in `p` from now on (Fp32 after load).
    void setPrecision(Precision p) { m_precision = p; }
    /// The precision the layer runs in on the AVX-512 engine.
    Precision precision() const { return m_precision; }

    /// Multiply-adds x 2 per output pixel (the layer's FLOP per pixel, without padding).
    double flopPerPixel() const { return 2.0 * m_k * m_k * m_in * m_out; }

    /// Output channels rounded up to 8; the padded weights [ky][kx][ci][co] and bias are zero
    /// there.
    int paddedOutChannels() const { return m_outPadded; }
    const float* paddedWeights() const { return m_wp.data(); }
    const float* paddedBias() const { return m_bp.data(); }

private:
    cpu::ConvArgs args(const Image* up, const Image& same, bool relu) const;

    int m_in = 0, m_out = 0, m_k = 0;
    int m_outPadded = 0; ///< output channels rounded up to 8 (vector lanes)
    std::vector<float> m_wp; ///< [ky][kx][ci][co padded to 8], zero padding
    std::vector<float> m_bp; ///< [co padded to 8]
    int m_outPadded16 = 0; ///< output channels rounded up to 16 (AVX-512 lanes)
    std::vector<float> m_wp16; ///< [ky][kx][ci][co padded to 16], zero padding
    std::vector<float> m_bp16; ///< [co padded to 16]
    std::vector<float> m_wt16; ///< at most cpu::kFewOutputs outputs: [ky][kx][co][ci padded to 16]
    /// bf16 weights [ky][kx][ci pair][co padded to 16][2] (other layers than m_wt16's)
    std::vector<std::uint16_t> m_wbf16;
    /// m_wt16's layers in bf16: [ky][co][kx][ci padded to 16], each (ky, co) run padded to
    /// cpu::fewOutputsChunks x 32 values (cpu::ConvArgs::wtbf16)
    std::vector<std::uint16_t> m_wtbf16;
    /// m_wbf16 with each tap's pairs padded to (in rounded up to 16) / 2, where the CPU runs AMX
    std::vector<std::uint16_t> m_wamx;
    /// Elements of m_wamx before its first weight: 0-31, so that the weights start on a 64-byte
    /// boundary of this allocation (a tile row in one cache line; a copied layer stays correct).
    std::size_t m_wamxOffset = 0;
    Precision m_precision = Precision::Fp32;
};

/// D: 2x2 average pooling of an image with even size into `out` (half size).
void down2(const Image& in, Image& out);
/// Rows [y0, y1) of the same into `out`, already of half size, on the calling thread.
void down2Rows(const Image& in, Image& out, int y0, int y1);

} // namespace afn::nn
