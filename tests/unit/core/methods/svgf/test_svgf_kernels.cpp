// SPDX-License-Identifier: Apache-2.0
// SVGF's vectorised row kernels (methods/svgf/kernels.h) against a plain scalar evaluation of the
// documented formulas (methods/svgf/guide.h, kernels.h), in double precision, on random planes:
// every guide combination (normal and/or depth or neither), steps 1 to 16 (the per-lane path at the
// borders included), a width that is not a multiple of the vector width. A kernel that reads the
// wrong plane, offset or weight (as a depth tap reading the normals' y once did) fails here even
// where the method-level tests still see a plausible image.
#include "methods/svgf/kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace {

using namespace afn::svgf;

constexpr int kW = 37, kH = 23; // not multiples of the 8 lanes; step 16 leaves the padded row

struct Scene {
    Planes in, invPhi;
    Guide guide;
};

Scene randomScene(bool hasNormal, bool hasDepth, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Scene s;
    s.in.resize(kW, kH, kColorPlanes);
    s.invPhi.resize(kW, kH, 1);
    s.guide.planes.resize(kW, kH, kGuidePlanes);
    s.guide.hasNormal = hasNormal;
    s.guide.hasDepth = hasDepth;
    s.guide.sigmaZ = 1.0f;
    s.guide.sigmaN = 16.0f; // a power of two, as the default 128, with fewer vanishing weights
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float c[3];
            for (int k = 0; k < 3; ++k)
                s.in.row(k, y)[x] = c[k] = 2.0f * u(rng);
            s.in.row(kVariance, y)[x] = 0.5f * u(rng);
            s.in.row(kLuminance, y)[x] = luminance(c);
            s.invPhi.row(0, y)[x] = 0.5f + 2.0f * u(rng);
            // Normals near +z (so that many taps keep a weight), unit length.
            float n[3] = { 0.3f * (u(rng) - 0.5f), 0.3f * (u(rng) - 0.5f), 1.0f };
            const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; ++k)
                s.guide.planes.row(kNormalX + k, y)[x] = n[k] / len;
            // A sloped depth with noise, its gradient as the guide would store it.
            s.guide.planes.row(kDepth, y)[x] = 5.0f + 0.05f * x + 0.02f * y + 0.01f * u(rng);
            s.guide.planes.row(kDepthDx, y)[x] = 0.05f;
            s.guide.planes.row(kDepthDy, y)[x] = 0.02f;
        }
    return s;
}

float plane(const Planes& p, int k, int x, int y)
{
    return p.row(k, y)[x];
}

/// One output pixel of the à-trous iteration, evaluated literally.
struct Expected {
    double rgb[3], variance, luminance;
};

Expected scalarAtrous(const Scene& s, int step, int x, int y)
{
    const double b3[3] = { 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0 };
    const Guide& g = s.guide;
    double cp[3];
    for (int k = 0; k < 3; ++k)
        cp[k] = plane(s.in, k, x, y);
    const double lp = plane(s.in, kLuminance, x, y), invPhi = plane(s.invPhi, 0, x, y);
    double ws = 0.0, vsum = 0.0, dc[3] = {};
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            const int qx = x + i * step, qy = y + j * step;
            if (qx < 0 || qx >= kW || qy < 0 || qy >= kH)
                continue;
            const double h = b3[std::abs(i)] * b3[std::abs(j)];
            double w = h;
            if (i != 0 || j != 0) {
                double e = std::abs(lp - plane(s.in, kLuminance, qx, qy)) * invPhi;
                if (g.hasDepth) {
                    const double zp = plane(g.planes, kDepth, x, y);
                    const double grad = plane(g.planes, kDepthDx, x, y) * (i * step)
                        + plane(g.planes, kDepthDy, x, y) * (j * step);
                    e += std::abs(zp - plane(g.planes, kDepth, qx, qy))
                        / (g.sigmaZ * std::abs(grad) + 1e-4 * std::abs(zp) + 1e-30);
                }
                double wn = 1.0;
                if (g.hasNormal) {
                    double d = 0.0;
                    for (int k = 0; k < 3; ++k)
                        d += plane(g.planes, kNormalX + k, x, y)
                            * plane(g.planes, kNormalX + k, qx, qy);
                    wn = std::pow(std::max(0.0, d), static_cast<double>(g.sigmaN));
                }
                w = h * std::exp(-e) * wn;
            }
            ws += w;
            vsum += w * w * plane(s.in, kVariance, qx, qy);
            for (int k = 0; k < 3; ++k)
                dc[k] += w * (plane(s.in, k, qx, qy) - cp[k]);
        }
    Expected r {};
    for (int k = 0; k < 3; ++k)
        r.rgb[k] = std::max(0.0, cp[k] + dc[k] / ws);
    r.variance = vsum / (ws * ws);
    r.luminance = 0.2126 * r.rgb[0] + 0.7152 * r.rgb[1] + 0.0722 * r.rgb[2];
    return r;
}

void expectNear(double expected, float got, const char* what, int x, int y)
{
    EXPECT_NEAR(got, expected, 1e-5 + 1e-4 * std::abs(expected))
        << what << " at (" << x << ", " << y << ")";
}

class SvgfAtrousKernel : public ::testing::TestWithParam<std::tuple<bool, bool, int>> { };

TEST_P(SvgfAtrousKernel, MatchesTheScalarFormula)
{
    const auto [hasNormal, hasDepth, step] = GetParam();
    const Scene s = randomScene(hasNormal, hasDepth, 7u + step);
    Planes out;
    out.resize(kW, kH, kColorPlanes);
    const AtrousArgs args { &s.in, &s.invPhi, &s.guide, &out, step };
    atrousRows(args, 0, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const Expected e = scalarAtrous(s, step, x, y);
            for (int k = 0; k < 3; ++k)
                expectNear(e.rgb[k], plane(out, k, x, y), "colour", x, y);
            expectNear(e.variance, plane(out, kVariance, x, y), "variance", x, y);
            expectNear(e.luminance, plane(out, kLuminance, x, y), "luminance", x, y);
        }
}

INSTANTIATE_TEST_SUITE_P(GuidesAndSteps, SvgfAtrousKernel,
    ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Values(1, 2, 4, 8, 16)));

TEST(SvgfInvPhiKernel, MatchesTheScalarFormula)
{
    const Scene s = randomScene(true, true, 3u);
    const float sigmaL = 4.0f;
    Planes invPhi;
    invPhi.resize(kW, kH, 1);
    invPhiRows(s.in, sigmaL, invPhi, 0, kH);
    const double g[3] = { 0.25, 0.5, 0.25 }; // the 3x3 Gaussian per axis, renormalised in-image
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            double sum = 0.0, wsum = 0.0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qx >= kW || qy < 0 || qy >= kH)
                        continue;
                    const double w = g[dx + 1] * g[dy + 1];
                    sum += w * plane(s.in, kVariance, qx, qy);
                    wsum += w;
                }
            const double expected = 1.0 / (sigmaL * std::sqrt(std::max(0.0, sum / wsum)) + 1e-10);
            expectNear(expected, plane(invPhi, 0, x, y), "invPhiL", x, y);
        }
}

} // namespace
