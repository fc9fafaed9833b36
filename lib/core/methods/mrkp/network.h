// SPDX-License-Identifier: Apache-2.0
// The MR-KP inference graph (training/afn/baselines/mrkp.py is the definition, with every choice
// the papers leave open; same tensor names):
//   x = [T(cta), albedo, normal01, depth01]                          10 ch, padded to 16
//   e0 = relu(enc0(x)); e_l = relu(enc{l}(D e_{l-1}))                  l = 1..4 (1/16)
//   y_4 = e_4; y_l = relu(dec{l}([relu(up{l}(y_{l+1})), e_l]))         up = 2x2 stride-2 transposed
//   head_l = head{l}(y_l), 26 ch (25 kernel logits + blend logit)      l = 0, 1, 2
//   filtering: methods/mrkp/kernels.h; level blending: nn/scale_fusion.h
// D = 2x2 average pooling.
#pragma once

#include "base/image.h"
#include "nn/baseline_input.h"
#include "nn/conv.h"
#include "nn/conv_transpose.h"
#include "nn/weights.h"

#include <array>

namespace afn::mrkp {

constexpr int kLevels = 5; ///< encoder levels (full .. 1/16)
constexpr int kFilterLevels = 3; ///< kernel-predicting levels (full, 1/2, 1/4)

class Network {
public:
    /// Build the graph from an archive (metadata format=mrkp); throws "invalid or corrupted
    /// weights" on any mismatch.
    void load(const nn::WeightsArchive& weights);
    bool loaded() const { return m_loaded; }

    /// Denoise one frame: `out` = demodulated irradiance (3 ch, W x H).
    void run(const nn::BaselineFeatureViews& in, Image& out);

    /// FLOP per frame of the last run (convolutions and the kernel filtering, padded pixels).
    double flopPerFrame() const { return m_flop; }
    /// Parameter count (weights and biases).
    long parameters() const;

private:
    bool m_loaded = false;
    std::array<nn::Conv, kLevels> m_enc;
    std::array<nn::ConvTranspose2x2, kLevels - 1> m_up;
    std::array<nn::Conv, kLevels - 1> m_dec;
    std::array<nn::Conv, kFilterLevels> m_head;
    Image m_x, m_colorTa;
    std::array<Image, kLevels> m_e, m_pooled, m_cat, m_y;
    std::array<Image, kFilterLevels> m_heads, m_color, m_filtered;
    double m_flop = 0.0;
};

} // namespace afn::mrkp
