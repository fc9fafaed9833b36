// SPDX-License-Identifier: Apache-2.0
// The network input of the learned baselines (ONND, MR-KP; training/afn/baselines/common.py):
// the shared protocol of the NBGD, WSKPN and MR-KP papers, 10 channels
//   x = [T(cta), albedo, normal01, depth01],  T(v) = clip(max(v, 0)^(1/2.2), 0, 1)
// where cta is the TA-accumulated demodulated colour (the afn method's "accumulated" feature).
// Inputs are padded at the right/bottom to a multiple of `padMultiple` by edge replication (as
// PyTorch's F.pad(mode="replicate")); the graph runs on the padded frame and the output is cropped.
#pragma once

#include "base/image.h"

namespace afn::nn {

/// The four feature images (all W x H): cta 3 ch (linear HDR, >= 0), albedo 3 ch, normal01 3 ch,
/// depth01 1 ch.
struct BaselineFeatures {
    const Image* colorTa = nullptr;
    const Image* albedo = nullptr;
    const Image* normal01 = nullptr;
    const Image* depth01 = nullptr;
};

constexpr int kBaselineInputChannels = 10;

/// Round n up to a multiple of m.
inline int paddedSize(int n, int m)
{
    return (n + m - 1) / m * m;
}

/// Build the padded network input `x` (10 ch) and the padded cta (3 ch, linear); throws
/// InvalidArgument when a feature is missing or of the wrong shape (`what` names the method).
void buildBaselineInput(
    const BaselineFeatures& f, int padMultiple, Image& x, Image& colorTa, const char* what);

/// The top-left W x H (3 channels) of `padded` into `out`.
void cropTo(const Image& padded, int w, int h, Image& out);

} // namespace afn::nn
