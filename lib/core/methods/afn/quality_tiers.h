// SPDX-License-Identifier: Apache-2.0
// AFN's quality tiers (quality=fast|balanced|high, filter/quality.h). The choice:
//   fast      the network without its refinement: o = i, the fused output of filtering + fusion,
//             computed by the whole-frame stages (not striped: more memory per megapixel)
//             (network.h). Refinement is a residual (o = i + ref(...)), so i is the network's own
//             estimate before it; the weights are the same. Weights without a refinement
//             (ablation variants) and AFN large (network_large.h) run as balanced.
//   balanced  the network as trained (Network::run), bit-identical to afn without the parameter.
//   high      a self-ensemble over the flips the network was trained with (training/afn/dataset.py
//             flips every crop horizontally and vertically, all inputs alike, normals unchanged):
//             the network runs on the frame as given, flipped left-right, upside down and both;
//             each output is flipped back and the four are averaged (test-time augmentation).
//             The temporal history is the shared stages' (reprojection, accumulation, aux
//             prefilter), built once per frame from the unflipped frame; the network itself keeps
//             no state, so every pass sees the same frame and history, only mirrored. Four
//             network passes: about 4x the network's time, the stages' time once.
// Measured cost and error of each tier: docs/quality.md.
#pragma once

#include "filter/quality.h"
#include "methods/afn/network.h"

namespace afn::afnet {

/// Stage times and FLOP of one frame summed over the tier's network passes (stats.afn.*).
struct TierStageTotals {
    double ms[Network::kStages] = {};
    double flop[Network::kStages] = {};
    double inputMs = 0.0; ///< of ms[prediction], Network::predictionInputMs
};

/// Runs `net` on `in` as `tier` asks; `out` = o (3 ch, demodulated, W x H, not clamped).
/// `work` (Frame::work, may be null or empty) lets balanced skip stripes without work
/// (Network::run); fast and high compute every pixel (their passes are not striped).
class TierRunner {
public:
    void run(QualitySettings::Tier tier, Network& net, const Inputs& in, Image& out,
        const Image* work = nullptr);
    const TierStageTotals& totals() const { return m_totals; }

private:
    void runFast(Network& net, const Inputs& in, Image& out);
    void runHigh(Network& net, const Inputs& in, Image& out);
    void add(const Network& net); ///< add the last Network::run's stage times and FLOP

    TierStageTotals m_totals;
    Image m_flipped[6], m_pass; // high: flipped inputs (history01 last), one pass's output
};

/// `dst` = `src` mirrored left-right (flipX) and/or upside down (flipY); any channel count.
void flipImage(const Image& src, bool flipX, bool flipY, Image& dst);

} // namespace afn::afnet
