// SPDX-License-Identifier: Apache-2.0
// SVGF edge-stopping guides (see methods/svgf/guide.h).
#include "methods/svgf/guide.h"

#include "base/parallel.h"
#include "cpu/rgb_rows.h"
#include "cpu/target.h"

#include <cmath>

namespace afn::svgf {

namespace {

/// The one-sided difference of smaller magnitude: the forward one (next - z) where it is smaller,
/// else the backward one, written as -(previous - z) (the same bits as before, -0 included).
inline float smallerDifference(float previous, float z, float next)
{
    const float backward = -(previous - z), forward = next - z;
    return std::fabs(forward) < std::fabs(backward) ? forward : backward;
}

/// Row y's depth gradient per axis (guide.h: the one-sided difference of smaller magnitude; one
/// side at the image's border, 0 without either): `up` and `down` are rows y - 1 and y + 1, null
/// outside the image. Branch-free over the inner columns, so the compiler vectorises it (the
/// clones of cpu/target.h); only subtractions, negations and comparisons: the same values on
/// every instruction set (tests/unit/core/methods/svgf/test_svgf_guide.cpp).
AFN_CPU_KERNEL_CLONES void depthGradientRow(
    const float* z, const float* up, const float* down, int w, float* dx, float* dy)
{
    if (w == 1)
        dx[0] = 0.0f;
    else {
        dx[0] = z[1] - z[0];
        dx[w - 1] = -(z[w - 2] - z[w - 1]);
    }
    for (int x = 1; x + 1 < w; ++x)
        dx[x] = smallerDifference(z[x - 1], z[x], z[x + 1]);
    if (up && down)
        for (int x = 0; x < w; ++x)
            dy[x] = smallerDifference(up[x], z[x], down[x]);
    else if (down)
        for (int x = 0; x < w; ++x)
            dy[x] = down[x] - z[x];
    else if (up)
        for (int x = 0; x < w; ++x)
            dy[x] = -(up[x] - z[x]);
    else
        for (int x = 0; x < w; ++x)
            dy[x] = 0.0f;
}

} // namespace

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
            if (hasNormal)
                cpu::deinterleaveRgbRow(f.normal.at(0, y), planes.row(kNormalX, y),
                    planes.row(kNormalY, y), planes.row(kNormalZ, y), w);
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
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            depthGradientRow(planes.row(kDepth, y), y > 0 ? planes.row(kDepth, y - 1) : nullptr,
                y + 1 < h ? planes.row(kDepth, y + 1) : nullptr, w, planes.row(kDepthDx, y),
                planes.row(kDepthDy, y));
    });
}

} // namespace afn::svgf
