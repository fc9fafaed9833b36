// SPDX-License-Identifier: Apache-2.0
// AVX-512 softmax + 7x7 kernel application of AFN's fused filtering pass (cpu/afn_fusion.cpp),
// used where cpu::activeIsa() is Avx512.
#pragma once

#include "base/image.h"

namespace afn::cpu {

/// Softmax over logits[0, 49) in place (methods/afn/fusion.h semantics: non-finite logits made
/// finite, maximum subtracted), then the normalised 7x7 kernel applied to the 3-channel `img` at
/// (x, y), written to rgb. `logits` must have 64 readable floats.
void softmaxApplyAvx512(float* logits, const Image& img, int x, int y, float* rgb);

} // namespace afn::cpu
