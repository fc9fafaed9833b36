// SPDX-License-Identifier: Apache-2.0
// Transposed convolution 2x2, stride 2 (PyTorch ConvTranspose2d(Cin, Cout, 2, stride=2)): every
// input pixel (x, y) writes the 2x2 output block at (2x, 2y):
//   out(2x + dx, 2y + dy, o) = bias[o] + sum_i in(x, y, i) * W[i][o][dy][dx].
// Used by MR-KP's decoder. Weights are repacked as [dy][dx][i][o] so the inner loop runs over
// contiguous output channels (vectorised by the compiler).
#pragma once

#include "base/image.h"
#include "nn/weights.h"

#include <string>
#include <vector>

namespace afn::nn {

class ConvTranspose2x2 {
public:
    /// Load "<name>.weight" (Cin, Cout, 2, 2) and "<name>.bias" (Cout); throws "invalid or
    /// corrupted weights" on a shape mismatch or Cin != expectedIn.
    void load(const WeightsArchive& a, const std::string& name, int expectedIn);

    int inChannels() const { return m_in; }
    int outChannels() const { return m_out; }

    /// Write the result into channels [offset, offset + outChannels()) of `out`, which must be
    /// (2 in.width(), 2 in.height()) with enough channels; optional ReLU.
    void run(const Image& in, Image& out, int offset, bool relu) const;

    /// Multiply-adds x 2 per output pixel.
    double flopPerPixel() const { return 2.0 * m_in * m_out; }

private:
    int m_in = 0, m_out = 0;
    std::vector<float> m_w; ///< [dy][dx][i][o]
    std::vector<float> m_b; ///< [o]
};

} // namespace afn::nn
