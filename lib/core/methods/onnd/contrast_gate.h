// SPDX-License-Identifier: Apache-2.0
// ONND's local-contrast gate (training/afn/baselines/onnd.py contrast_gate, the definition):
//   c = max(cta, 0); hi, lo = max, min of c over the 3x3 window (edges replicated), per channel
//   g = min(1, kGateGain * max_ch (hi - lo) / (hi + lo + kGateEps))
// The network's output is blended with the input colour by g (irradiance = c + g (net - c)), so a
// flat window (hi == lo exactly, black included) returns the input colour bit for bit: the stress
// properties "constant stays constant", "black stays black" and "a static scene reaches a fixed
// point" hold by construction, whatever the weights and the recurrent state. Max/min rather than
// a standard deviation: a mean of equal floats need not equal them.
#pragma once

#include "base/image.h"

namespace afn::onnd {

constexpr int kGateRadius = 1; ///< 3x3 window
constexpr float kGateGain = 8.0f; ///< the gate is fully open from hi/lo ~ 1.29 on
constexpr float kGateEps = 1e-4f; ///< keeps the ratio finite at black

/// The gate (1 channel, in [0, 1]) of the colour `c` (3 channels, negatives read as 0).
void contrastGate(const Image& c, Image& gate);

} // namespace afn::onnd
