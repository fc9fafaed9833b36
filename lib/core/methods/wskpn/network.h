// SPDX-License-Identifier: Apache-2.0
// WSKPN's inference network (Fan et al. 2021; training/afn/baselines/wskpn.py is the reference and
// states every choice the paper leaves open): the six RepVGG blocks folded at export into single
// 5x5 convolutions conv1 ... conv6 (10 -> 14 -> 14 -> 14 -> 14 -> 14 -> 12, leaky ReLU 0.1 after
// conv1 ... conv5; widths are read from the archive), then the weight-sharing filter
// (weight_sharing_filter.h) on the linear HDR TA-1spp colour.
//
// Cost (default widths): 54,600 FLOP per pixel in the convolutions (2 per multiply-add) plus ~204
// in the filter; 27,382 parameters.
#pragma once

#include "base/image.h"
#include "nn/conv.h"
#include "nn/weights.h"

#include <array>

namespace afn::wskpn {

/// Layers of the folded network.
constexpr int kLayers = 6;
/// Box windows 3, 5, ..., 13.
constexpr int kWindows = 6;
/// Head channels: kWindows weight logits, then kWindows fusion logits.
constexpr int kHeadChannels = 2 * kWindows;
/// Leaky ReLU slope between the layers.
constexpr float kLeakySlope = 0.1f;

class Network {
public:
    /// Load conv1 ... conv6 (5x5) from a "format=wskpn" archive; throws "invalid or corrupted
    /// weights" on any mismatch (wrong format, shapes, kernel size).
    void load(const nn::WeightsArchive& a);
    bool loaded() const { return m_layers[0].loaded(); }

    /// Filtered demodulated colour from the 10-channel input (nn/baseline_input.h) and the
    /// linear HDR colour cta (both w x h).
    void run(const Image& input, const Image& cta, Image& out);

    /// The head of the last run (w x h x 12: weight logits, fusion logits).
    const Image& head() const { return m_head; }
    /// Multiply-adds x 2 per pixel of the convolutions.
    double flopPerPixel() const;

private:
    std::array<nn::Conv, kLayers> m_layers;
    Image m_a, m_b, m_head, m_products, m_sums;
};

} // namespace afn::wskpn
