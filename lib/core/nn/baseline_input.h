// SPDX-License-Identifier: Apache-2.0
// The input of the learned baselines WSKPN and NBGD (training/afn/baselines/inputs.py): 10
// channels [T(cta) 3, albedo 3, normal01 3, depth01 1] with T(x) = clip(max(x, 0)^(1/2.2), 0, 1).
// cta is the BMFR temporal accumulation of the demodulated 1-spp colour (the shared stages), and
// albedo, normal01 and depth01 are afn's features (methods/afn/features.h: the same scaling the
// training data was prepared with through afntool --features, reused so the two cannot drift).
#pragma once

#include "base/image.h"
#include "filter/frame.h"

namespace afn::nn {

/// Channels of the baselines' network input.
constexpr int kBaselineInputChannels = 10;

/// The per-frame features: the albedo (1 without one) and afn's normal01 / depth01 of `in`.
struct BaselineFeatures {
    Image albedo, normal01, depth01;
    void compute(const Frame& in);
};

/// out (w x h x 10) = [T(cta), albedo, normal01, depth01].
void baselineInput(const Image& cta, const BaselineFeatures& f, Image& out);

/// x = x >= 0 ? x : slope * x, in place.
void leakyRelu(Image& x, float slope);

} // namespace afn::nn
