// SPDX-License-Identifier: Apache-2.0
// NBGD's inference (Meng et al. 2020; training/afn/baselines/nbgd.py is the reference and states
// every choice the paper leaves open): the guide network guide1 (5x5, 10 -> 20, leaky ReLU 0.2)
// and guide2 (5x5, 20 -> 5, sigmoid): guides g_k = 255 s_k (k = 0, 1, 2) and blend weights
// w1 = s_3, w2 = s_4; three bilateral grids (bilateral_grid.h) with (spatial, range) steps (4, 4),
// (8, 8), (16, 16), grid k splatted and sliced with g_k, on the linear HDR TA-1spp colour;
// output w1 b1 + w2 b2 + (1 - w1 - w2) b3.
//
// Cost: 15,000 FLOP per pixel in the guide network (2 per multiply-add), ~200 in splat + slice
// (memory-bound); 7,525 parameters.
#pragma once

#include "base/image.h"
#include "methods/nbgd/bilateral_grid.h"
#include "nn/conv.h"
#include "nn/weights.h"

#include <array>

namespace afn::nbgd {

/// Grids and their (spatial step in pixels, range step in guide units).
constexpr int kGrids = 3;
constexpr std::array<std::array<int, 2>, kGrids> kGridSteps { { { 4, 4 }, { 8, 8 }, { 16, 16 } } };
/// Guide network output: 3 guides, 2 blend weights.
constexpr int kGuideOutputs = 5;
constexpr float kLeakySlope = 0.2f;

class Network {
public:
    /// Load guide1, guide2 (5x5) from a "format=nbgd" archive; throws "invalid or corrupted
    /// weights" on any mismatch.
    void load(const nn::WeightsArchive& a);
    bool loaded() const { return m_guide2.loaded(); }

    /// Filtered demodulated colour from the 10-channel input (nn/baseline_input.h) and the linear
    /// HDR colour cta (both w x h).
    void run(const Image& input, const Image& cta, Image& out);

    /// Sigmoid outputs of the last run (w x h x 5; channels 0-2 x 255 are the guides).
    const Image& guides() const { return m_guides; }
    /// The last run's sliced grid k (w x h x 3).
    const Image& sliced(int k) const { return m_sliced[k]; }
    double flopPerPixel() const { return m_guide1.flopPerPixel() + m_guide2.flopPerPixel(); }

private:
    nn::Conv m_guide1, m_guide2;
    Image m_hidden, m_guides;
    Image m_scaled; ///< the grids' guides in [0, 255], cta's size (kept across frames)
    std::array<BilateralGrid, kGrids> m_grids;
    std::array<Image, kGrids> m_sliced;
};

} // namespace afn::nbgd
