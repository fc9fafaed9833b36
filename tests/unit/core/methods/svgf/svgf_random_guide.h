// SPDX-License-Identifier: Apache-2.0
// A random guide pixel for SVGF's kernel tests (test_svgf_kernels.cpp,
// test_svgf_variance_kernel.cpp): a unit normal near +z (x and y in [-spread/2, spread/2) before
// normalising, so that many taps keep a weight) and a sloped depth with noise, its gradient as
// methods/svgf/guide.h stores it.
#pragma once

#include "methods/svgf/guide.h"

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

} // namespace afntest
