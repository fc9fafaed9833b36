// SPDX-License-Identifier: Apache-2.0
// Convolution layers of the AFN engine: direct (im2col-free) k x k convolutions, stride 1, zero
// padding k/2, on interleaved (H, W, C) images, with oneTBB over rows. The inner loop runs over
// the output channels with the weights stored [tap][in][out], so it vectorises.
#pragma once

#include "afn_weights.h"
#include "image.h"

#include <string>
#include <vector>

namespace afn {

/// Most output channels of one layer (the 7x7 kernel head has 50).
constexpr int kAfnMaxChannels = 256;

/// One conv layer: PyTorch Conv2d(Cin, Cout, k, padding=k/2) with bias.
class AfnConv {
public:
    /// Load "<name>.weight" (Cout, Cin, k, k) and "<name>.bias" (Cout). Throws "invalid or
    /// corrupted weights" if the shapes are inconsistent, k is not 1 or 3, Cin differs from
    /// `expectedIn`, or Cout from `expectedOut` (when >= 0).
    void load(const WeightsArchive& a, const std::string& name, int expectedIn, int expectedOut = -1);

    int inChannels() const { return m_in; }
    int outChannels() const { return m_out; }
    int kernelSize() const { return m_k; }
    bool loaded() const { return m_out > 0; }

    /// out = conv(concat(U(up), same)), optionally followed by ReLU. Channels [0, up.channels)
    /// of the input read `up` (half of out's size, nearest 2x upsampling, never materialised),
    /// the others read `same` (out's size). `up` may be null. `out` is resized to same's size.
    void run(const Image* up, const Image& same, Image& out, bool relu) const;

    /// 1x1 layers only: acc[co] = bias + sum_ci W[co][ci] * in[ci], in = concat(a[0..na), b[0..nb)).
    void evalPixel(const float* a, int na, const float* b, int nb, float* acc) const;

private:
    int m_in = 0, m_out = 0, m_k = 0;
    std::vector<float> m_w; ///< [ky][kx][ci][co]
    std::vector<float> m_b; ///< [co]
};

/// D: 2x2 average pooling of an image with even size into `out` (half size).
void afnDown2(const Image& in, Image& out);

} // namespace afn
