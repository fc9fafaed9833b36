// SPDX-License-Identifier: Apache-2.0
// The input of the learned baselines WSKPN, NBGD (training/afn/baselines/inputs.py), ONND and
// MR-KP (training/afn/baselines/common.py): the shared protocol of the NBGD, WSKPN and MR-KP
// papers, 10 channels [T(cta) 3, albedo 3, normal01 3, depth01 1] with
// T(x) = clip(max(x, 0)^(1/2.2), 0, 1).
// cta is the BMFR temporal accumulation of the demodulated 1-spp colour (the shared stages), and
// albedo, normal01 and depth01 are afn's features (stages/feature_scaling.h: the same scaling the
// training data was prepared with through afntool --features, reused so the two cannot drift).
// ONND and MR-KP run on inputs padded at the right/bottom to a multiple of `padMultiple` by edge
// replication (as PyTorch's F.pad(mode="replicate")); their output is cropped back.
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

/// out (w x h x 10) = [T(cta), albedo, normal01, depth01] (WSKPN, NBGD).
void baselineInput(const Image& cta, const BaselineFeatures& f, Image& out);

/// The four feature images of the padded input (all W x H): cta 3 ch (linear HDR, >= 0),
/// albedo 3 ch, normal01 3 ch, depth01 1 ch (ONND, MR-KP).
struct BaselineFeatureViews {
    const Image* colorTa = nullptr;
    const Image* albedo = nullptr;
    const Image* normal01 = nullptr;
    const Image* depth01 = nullptr;
};

/// Round n up to a multiple of m.
inline int paddedSize(int n, int m)
{
    return (n + m - 1) / m * m;
}

/// Build the padded network input `x` (10 ch) and the padded cta (3 ch, linear); throws
/// InvalidArgument when a feature is missing or of the wrong shape (`what` names the method).
void buildBaselineInput(
    const BaselineFeatureViews& f, int padMultiple, Image& x, Image& colorTa, const char* what);

/// The top-left W x H (3 channels) of `padded` into `out`.
void cropTo(const Image& padded, int w, int h, Image& out);

} // namespace afn::nn
