// SPDX-License-Identifier: Apache-2.0
// Convolution layers of the AFN engine: direct (im2col-free) k x k convolutions, stride 1, zero
// padding k/2, on interleaved (H, W, C) images, with oneTBB over rows. The inner loop runs over
// blocks of 8 output channels x 4 output pixels (weights stored [tap][in][out padded to 8]);
// the row loop is compiled for x86-64-v3 (AVX2+FMA) and baseline x86-64, chosen at load time.
#pragma once

#include "base/image.h"
#include "nn/weights.h"

#include <string>
#include <vector>

namespace afn::nn {

/// Most output channels of one layer (the 7x7 kernel head has 50).
constexpr int kMaxChannels = 256;

/// One conv layer: PyTorch Conv2d(Cin, Cout, k, padding=k/2) with bias.
class Conv {
public:
    /// Load "<name>.weight" (Cout, Cin, k, k) and "<name>.bias" (Cout). Throws "invalid or
    /// corrupted weights" if the shapes are inconsistent, k is not 1 or 3, Cin differs from
    /// `expectedIn`, or Cout from `expectedOut` (when >= 0).
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

    /// Output channels rounded up to 8; the padded weights [ky][kx][ci][co] and bias are zero
    /// there.
    int paddedOutChannels() const { return m_outPadded; }
    const float* paddedWeights() const { return m_wp.data(); }
    const float* paddedBias() const { return m_bp.data(); }

private:
    int m_in = 0, m_out = 0, m_k = 0;
    int m_outPadded = 0; ///< output channels rounded up to 8 (vector lanes)
    std::vector<float> m_wp; ///< [ky][kx][ci][co padded to 8], zero padding
    std::vector<float> m_bp; ///< [co padded to 8]
};

/// D: 2x2 average pooling of an image with even size into `out` (half size).
void down2(const Image& in, Image& out);

} // namespace afn::nn
