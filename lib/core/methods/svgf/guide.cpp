// SPDX-License-Identifier: Apache-2.0
// SVGF edge-stopping guides (see methods/svgf/guide.h).
#include "methods/svgf/guide.h"

#include "base/parallel.h"

namespace afn::svgf {

void Guide::build(const Frame& f, const Settings& s)
{
    sigmaZ = s.sigmaZ;
    sigmaN = s.sigmaN;
    integerSigmaN = sigmaN == std::floor(sigmaN) && sigmaN <= 65536.0f;
    normal = f.hasNormal() ? &f.normal : nullptr;
    const int w = f.width, h = f.height;
    if (f.hasDepth()) {
        depth = f.depth;
    } else if (f.hasPosition() && f.camera.valid) {
        depth.resize(w, h, 1);
        const auto& M = f.camera.viewProjection;
        parallelRows(h, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < w; ++x) {
                    const float* p = f.position.at(x, y);
                    depth(x, y, 0) = p[0] * M[3] + p[1] * M[7] + p[2] * M[11] + M[15];
                }
        });
    } else {
        depth = Image();
        gradient = Image();
        return;
    }
    gradient.resize(w, h, 2);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float z = depth(x, y, 0);
                auto axis = [&](int dx, int dy) {
                    float best = 0.0f;
                    bool any = false;
                    for (int sgn = -1; sgn <= 1; sgn += 2) {
                        const int nx = x + sgn * dx, ny = y + sgn * dy;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h)
                            continue;
                        const float d = sgn * (depth(nx, ny, 0) - z);
                        if (!any || std::fabs(d) < std::fabs(best))
                            best = d;
                        any = true;
                    }
                    return best;
                };
                gradient(x, y, 0) = axis(1, 0);
                gradient(x, y, 1) = axis(0, 1);
            }
    });
}

} // namespace afn::svgf
