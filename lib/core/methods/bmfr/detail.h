// SPDX-License-Identifier: Apache-2.0
// Noise-aware detail restoration after BMFR's regression (detail.cpp has the rule and why).
#pragma once

#include "base/image.h"

namespace afn::bmfr {

/// Write fit + k (accumulated - fit) into `current` (the frame's demodulated colour, 3 ch, read
/// first for the noise estimate, then overwritten), k from the residual against the accumulated
/// colour's estimated noise. `length`: the accumulation's history length after this frame;
/// `alphaMin` and `effectiveLimit`: its minimum blend and effective sample count.
void restoreDetail(const Image& accumulated, const Image& length, float alphaMin,
    float effectiveLimit, const Image& fit, Image& current);

} // namespace afn::bmfr
