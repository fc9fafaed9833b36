// SPDX-License-Identifier: Apache-2.0
// Edge-stopping guides shared by SVGF's variance estimate and à-trous passes (Schied et al. 2017):
//   w = h * exp(-|z_p - z_q| / (sigmaZ * |grad z(p) . (p - q)| + eps_z) - |l_p - l_q| / phiL)
//         * max(0, n_p . n_q)^sigmaN
// A guide whose buffer is missing contributes 1. Depth is the frame's depth, or the view depth
// (clip w) of the world position under the current camera, or absent. Its gradient is the
// one-sided difference of smaller magnitude per axis (robust at silhouettes); eps_z = 1e-4 * |z_p|
// keeps the test scale-free. The guides are kept as planes (methods/svgf/planes.h) for the
// vectorised kernels (methods/svgf/kernels.h), which evaluate the formula above.
#pragma once

#include "filter/frame.h"
#include "methods/svgf/planes.h"
#include "methods/svgf/settings.h"

#include <cmath>

namespace afn::svgf {

/// Planes of Guide::planes.
enum GuidePlane { kNormalX, kNormalY, kNormalZ, kDepth, kDepthDx, kDepthDy, kGuidePlanes };

/// Per-frame guide buffers for the edge-stopping functions.
struct Guide {
    Planes planes; ///< GuidePlane order; normal planes valid if hasNormal, depth ones if hasDepth
    bool hasNormal = false;
    bool hasDepth = false;
    float sigmaZ = 1.0f;
    float sigmaN = 128.0f;
    bool integerSigmaN = true; ///< max(0, n.n')^sigmaN by squaring (sigmaN = 128: 7 products)

    /// Build from the frame (depth source as in the file comment).
    void build(const Frame& f, const Settings& s);
};

/// Rec. 709 luminance.
inline float luminance(const float* c)
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

} // namespace afn::svgf
