// SPDX-License-Identifier: Apache-2.0
// The guide of SVGF's kernel tests (test_svgf_kernels.cpp, test_svgf_variance_kernel.cpp): a
// random guide pixel (a unit normal near +z, x and y in [-spread/2, spread/2) before normalising,
// so that many taps keep a weight, and a sloped depth with noise, its gradient as
// methods/svgf/guide.h stores it), and the guide's terms of a tap's weight in double precision.
#pragma once

#include "methods/svgf/guide.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace afntest {

inline void setRandomGuidePixel(afn::svgf::Guide& g, int x, int y, float spread, std::mt19937& rng)
{
    using namespace afn::svgf;
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    float n[3] = { spread * (u(rng) - 0.5f), spread * (u(rng) - 0.5f), 1.0f };
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
        g.planes.row(kNormalX + k, y)[x] = n[k] / len;
    g.planes.row(kDepth, y)[x] = 5.0f + 0.05f * x + 0.02f * y + 0.01f * u(rng);
    g.planes.row(kDepthDx, y)[x] = 0.05f;
    g.planes.row(kDepthDy, y)[x] = 0.02f;
}

/// The guide's terms of the weight of tap q for pixel p at offset (ox, oy) = q - p in pixels, in
/// double (methods/svgf/guide.h): the depth term's exponent (0 without depth) and
/// max(0, n_p . n_q)^sigmaN (1 without normals).
struct GuideTerms {
    double depth = 0.0, normal = 1.0;
};

inline GuideTerms scalarGuideTerms(
    const afn::svgf::Guide& g, int x, int y, int qx, int qy, double ox, double oy)
{
    using namespace afn::svgf;
    const auto at = [&](int k, int px, int py) -> double { return g.planes.row(k, py)[px]; };
    GuideTerms t;
    if (g.hasDepth) {
        const double z = at(kDepth, x, y);
        const double grad = at(kDepthDx, x, y) * ox + at(kDepthDy, x, y) * oy;
        t.depth = std::abs(z - at(kDepth, qx, qy))
            / (g.sigmaZ * std::abs(grad) + 1e-4 * std::abs(z) + 1e-30);
    }
    if (g.hasNormal) {
        double d = 0.0;
        for (int k = 0; k < 3; ++k)
            d += at(kNormalX + k, x, y) * at(kNormalX + k, qx, qy);
        t.normal = std::pow(std::max(0.0, d), static_cast<double>(g.sigmaN));
    }
    return t;
}

} // namespace afntest
