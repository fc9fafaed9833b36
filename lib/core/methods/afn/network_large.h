// SPDX-License-Identifier: Apache-2.0
// AFN large, the paper's architecture for high sample counts (Lee et al., Appendix VII-A: "3
// scales of 5x5 kernel maps K1, K2, K3 ... applied to the original and down-scaled 64spp images,
// and filtered images are fused progressively. Finally, large refinement modules are applied").
// training/afn/model_large.py is the definition, with every choice the paper leaves open; same
// tensor names. Weights with metadata variant=large; Network (network.h) runs this graph for them.
//   x = [T(c), albedo, normal01, depth01]                    10 ch, full res (padded to 8); no TA
//   e1..e3, d2, d1: AFN's half-res-start U-Net on x           (enc1..3, dec2, dec1)
//   K3 = softmax(head3(d2)) on D(D(c)) -> f3                  1/4, 5x5
//   [K2, a2] = head2(d1) on D(c) -> f2                        1/2
//   [K1, a1] = head1([U d1, x]) on c -> f1                    full res
//   o2 = fuseScales(f2, f3, a2); i = fuseScales(f1, o2, a1)   (nn/scale_fusion.h, Eq. 3 per scale)
//   o = i + refA(...); o = o + refB(...)                      two AFN refinement modules
// Kernels: softmax over 25 taps, tap j = (dy + 2) * 5 + (dx + 2), the image read with edge
// replication outside the frame. First version: whole frame (every layer stored at frame size,
// about 122 floats per padded pixel: 490 MB per megapixel), not in stripes like AFN; a work mask
// is not used (every row is computed).
#pragma once

#include "base/image.h"
#include "nn/conv.h"
#include "nn/weights.h"

#include <array>

namespace afn::afnet {

struct Inputs; // network.h

class LargeNetwork {
public:
    /// The layers (the CUDA engine packs them); refA1..3, refB1..3 are the two refinement modules.
    enum class Layer { Enc1, Enc2, Enc3, Dec2, Dec1, Head3, Head2, Head1, RefA1 };
    static constexpr int kLayers = 14;
    /// Layer `index` in Layer order (RefA1 + k for the k-th refinement layer).
    const nn::Conv& layer(int index) const;

    /// Build the graph from an archive (variant=large); throws "invalid or corrupted weights".
    void load(const nn::WeightsArchive& weights);

    /// `out` = o (3 ch, demodulated, W x H, not clamped) from in.color1 (the high-spp colour),
    /// in.albedo, in.normal01, in.depth01 (shapes checked by the caller; in.colorTa unused).
    /// ms[0..2] receive the milliseconds of prediction, filtering + fusion, refinement.
    void run(const Inputs& in, Image& out, double ms[3]);

    /// FLOP per frame of stage 0 (prediction), 1 (heads, filtering, fusion), 2 (refinement) at
    /// the last run's padded size (2 per multiply-add of the convolutions and the 5x5 filters).
    double stageFlop(int stage) const;

    /// Intermediates of the last run at the padded size (tests): fused i, f1, the fusion logits
    /// of the full scale (channel 25 of head1: alpha1 = sigmoid), o2 at 1/2, f3 at 1/4.
    const Image& fused() const { return m_fused; }
    const Image& filteredFull() const { return m_f1; }
    const Image& fullHead() const { return m_h1; }
    const Image& fusedHalf() const { return m_f2; }
    const Image& filteredQuarter() const { return m_f3; }

private:
    void prepare(const Inputs& in);
    void predict();
    void filterAndFuse();
    void refine();

    nn::Conv m_enc1, m_enc2, m_enc3, m_dec2, m_dec1, m_head1, m_head2, m_head3;
    std::array<nn::Conv, 6> m_ref; ///< refA1..3, refB1..3
    int m_padW = 0, m_padH = 0;
    Image m_x, m_c, m_cHalf, m_cQuarter, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3, m_d2, m_d1;
    Image m_h1, m_h2, m_h3, m_f1, m_f2, m_f3, m_fused, m_o, m_refIn, m_r1, m_r2, m_r3;
};

} // namespace afn::afnet
