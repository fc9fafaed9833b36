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
    hasNormal = f.hasNormal();
    hasDepth = f.hasDepth() || (f.hasPosition() && f.camera.valid);
    const int w = f.width, h = f.height;
    planes.resize(w, h, kGuidePlanes);
    const auto& M = f.camera.viewProjection;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            if (hasNormal) {
                float* n[3]
                    = { planes.row(kNormalX, y), planes.row(kNormalY, y), planes.row(kNormalZ, y) };
                for (int x = 0; x < w; ++x)
                    for (int k = 0; k < 3; ++k)
                        n[k][x] = f.normal(x, y, k);
            }
            if (!hasDepth)
                continue;
            float* z = planes.row(kDepth, y);
            for (int x = 0; x < w; ++x) {
                if (f.hasDepth()) {
                    z[x] = f.depth(x, y, 0);
                } else {
                    const float* p = f.position.at(x, y);
                    z[x] = p[0] * M[3] + p[1] * M[7] + p[2] * M[11] + M[15];
                }
            }
        }
    });
    if (!hasDepth)
        return;
    auto depth = [&](int x, int y) { return planes.row(kDepth, y)[x]; };
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float z = depth(x, y);
                auto axis = [&](int dx, int dy) {
                    float best = 0.0f;
                    bool any = false;
                    for (int sgn = -1; sgn <= 1; sgn += 2) {
                        const int nx = x + sgn * dx, ny = y + sgn * dy;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h)
                            continue;
                        const float d = sgn * (depth(nx, ny) - z);
                        if (!any || std::fabs(d) < std::fabs(best))
                            best = d;
                        any = true;
                    }
                    return best;
                };
                planes.row(kDepthDx, y)[x] = axis(1, 0);
                planes.row(kDepthDy, y)[x] = axis(0, 1);
            }
    });
}

} // namespace afn::svgf
