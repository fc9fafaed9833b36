// SPDX-License-Identifier: Apache-2.0
// Edge-stopping guides shared by SVGF's variance estimate and à-trous passes (Schied et al. 2017):
//   w = h * exp(-|z_p - z_q| / (sigmaZ * |grad z(p) . (p - q)| + eps_z) - |l_p - l_q| / phiL)
//         * max(0, n_p . n_q)^sigmaN
// A guide whose buffer is missing contributes 1. Depth is the frame's depth, or the view depth
// (clip w) of the world position under the current camera, or absent. Its gradient is the
// one-sided difference of smaller magnitude per axis (robust at silhouettes); eps_z = 1e-4 * |z_p|
// keeps the test scale-free.
#pragma once

#include "filter/frame.h"
#include "methods/svgf/settings.h"

#include <cmath>

namespace afn::svgf {

/// Per-frame guide buffers for the edge-stopping functions.
struct Guide {
    Image depth; ///< 1 ch, empty if no depth source
    Image gradient; ///< 2 ch depth gradient per pixel (dz/dx, dz/dy)
    const Image* normal = nullptr; ///< the frame's normals, or null
    float sigmaZ = 1.0f;
    float sigmaN = 128.0f;
    bool integerSigmaN = true;

    /// Build from the frame (depth source as in the file comment).
    void build(const Frame& f, const Settings& s);

    /// exp() argument of the depth term and the normal factor for taps p -> q at offset (dx, dy).
    float depthTerm(int px, int py, int qx, int qy, int dx, int dy) const
    {
        if (depth.empty())
            return 0.0f;
        const float zp = depth(px, py, 0), zq = depth(qx, qy, 0);
        const float* g = gradient.at(px, py);
        const float denom
            = sigmaZ * std::fabs(g[0] * dx + g[1] * dy) + 1e-4f * std::fabs(zp) + 1e-30f;
        return std::fabs(zp - zq) / denom;
    }
    float normalFactor(int px, int py, int qx, int qy) const
    {
        if (!normal)
            return 1.0f;
        const float* a = normal->at(px, py);
        const float* b = normal->at(qx, qy);
        const float d = std::fmax(0.0f, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
        return integerPower(d);
    }

private:
    float integerPower(float d) const
    {
        if (!integerSigmaN)
            return std::pow(d, sigmaN);
        // Exponentiation by squaring: sigmaN = 128 costs 7 multiplications instead of a pow().
        unsigned e = static_cast<unsigned>(sigmaN);
        float result = 1.0f, base = d;
        while (e) {
            if (e & 1u)
                result *= base;
            base *= base;
            e >>= 1u;
        }
        return result;
    }
};

/// Rec. 709 luminance.
inline float luminance(const float* c)
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

} // namespace afn::svgf
