// SPDX-License-Identifier: Apache-2.0
// SVGF's variance-estimate row kernels (methods/svgf/kernels.h varianceRows: portable 8 lanes,
// AVX-512 16 lanes where the CPU has it) against a plain scalar evaluation of the documented
// formulas in double precision, on random planes whose history lengths mix short and long ones
// within each vector: every guide combination, the default normal exponent 128 (the AVX-512
// kernel's unrolled squarings), another power of two and a non-integer one, widths that are not
// a multiple of the vector width (37, and 101 with blocks far from both borders), with and without
// spreading sparse samples (VarianceArgs::spread; the random moments give neighbourhoods on both
// sides of the sparse share's ramp).
#include "cpu/isa.h"
#include "methods/svgf/kernels.h"
#include "svgf_random_guide.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <tuple>

namespace {

using namespace afn::svgf;

constexpr int kH = 19;
constexpr float kPhiL = 4.0f, kVarianceHistory = 4.0f;

struct Scene {
    Planes in;
    Guide guide;
};

Scene randomScene(bool hasNormal, bool hasDepth, float sigmaN, int width, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float lengths[] = { 1.0f, 2.0f, 3.0f, 5.0f, 12.0f };
    Scene s;
    s.in.resize(width, kH, kIntegratedPlanes);
    s.guide.planes.resize(width, kH, kGuidePlanes);
    s.guide.hasNormal = hasNormal;
    s.guide.hasDepth = hasDepth;
    s.guide.sigmaZ = 1.0f;
    s.guide.sigmaN = sigmaN;
    s.guide.integerSigmaN = sigmaN == std::floor(sigmaN);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < width; ++x) {
            // The right half holds a few bright samples among dim ones: neighbourhoods whose
            // coefficient of variation lies on the sparse share's ramp (1.2-2.5), the left
            // half's below it.
            const float scale = x > width / 2 && u(rng) < 0.15f ? 16.0f : 2.0f;
            float c[3];
            for (int k = 0; k < 3; ++k)
                s.in.row(kIntRed + k, y)[x] = c[k] = scale * u(rng);
            const float l = luminance(c);
            s.in.row(kIntLuminance, y)[x] = l;
            s.in.row(kMoment1, y)[x] = l;
            s.in.row(kMoment2, y)[x] = l * l + 0.01f + 0.5f * u(rng);
            s.in.row(kHistoryLength, y)[x] = lengths[rng() % 5];
            afntest::setRandomGuidePixel(s.guide, x, y, 0.2f, rng);
        }
    return s;
}

double at(const Planes& p, int k, int x, int y)
{
    return p.row(k, y)[x];
}

struct Expected {
    double rgb[3], variance, luminance;
};

struct Sums {
    double ws = 0.0, c[3] = {}, m[2] = {};
};

/// The 7x7 cross-bilateral sums with the luminance term |l_p - l_q| * lumScale / phiL.
Sums crossBilateral(const Scene& s, int x, int y, double lumScale)
{
    const Planes& in = s.in;
    const Guide& g = s.guide;
    Sums r;
    double& ws = r.ws;
    double* c = r.c;
    double* m = r.m;
    for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= in.width() || qy >= in.height())
                continue;
            const afntest::GuideTerms t = afntest::scalarGuideTerms(g, x, y, qx, qy, dx, dy);
            const double e = lumScale
                    * std::abs(at(in, kIntLuminance, x, y) - at(in, kIntLuminance, qx, qy))
                    / (kPhiL + 1e-10)
                + t.depth;
            const double w = e < 87.0 ? std::exp(-e) * t.normal : 0.0;
            ws += w;
            for (int k = 0; k < 3; ++k)
                c[k] += w * at(in, kIntRed + k, qx, qy);
            for (int k = 0; k < 2; ++k)
                m[k] += w * at(in, kMoment1 + k, qx, qy);
        }
    return r;
}

/// kernels.h VarianceArgs and methods/svgf/denoiser.h, in double.
Expected scalarVariance(const Scene& s, int x, int y, bool spread)
{
    const Planes& in = s.in;
    Expected r {};
    const double len = at(in, kHistoryLength, x, y);
    if (len >= kVarianceHistory) {
        for (int k = 0; k < 3; ++k)
            r.rgb[k] = at(in, kIntRed + k, x, y);
        const double m1 = at(in, kMoment1, x, y);
        r.variance = std::max(0.0, at(in, kMoment2, x, y) - m1 * m1);
    } else {
        double lumScale = 1.0;
        if (spread) { // the sparse share of the guide-only estimate's moments
            const Sums g = crossBilateral(s, x, y, 0.0);
            const double m1 = g.m[0] / g.ws, m2 = g.m[1] / g.ws;
            const double cv = std::sqrt(std::max(0.0, m2 - m1 * m1)) / std::max(m1, 1e-20);
            lumScale
                = 1.0 - std::clamp((cv - kSparseCvLow) / (kSparseCvHigh - kSparseCvLow), 0.0, 1.0);
        }
        const Sums e = crossBilateral(s, x, y, lumScale);
        for (int k = 0; k < 3; ++k)
            r.rgb[k] = e.c[k] / e.ws;
        const double m1 = e.m[0] / e.ws, m2 = e.m[1] / e.ws;
        r.variance = std::max(0.0, m2 - m1 * m1) * 4.0 / len;
    }
    r.luminance = 0.2126 * r.rgb[0] + 0.7152 * r.rgb[1] + 0.0722 * r.rgb[2];
    return r;
}

void expectNear(double expected, float got, const char* what, int x, int y)
{
    EXPECT_NEAR(got, expected, 1e-5 + 1e-4 * std::abs(expected))
        << what << " at (" << x << ", " << y << ")";
}

class SvgfVarianceKernel
    : public ::testing::TestWithParam<std::tuple<afn::cpu::Isa, bool, bool, float, bool>> { };

TEST_P(SvgfVarianceKernel, MatchesTheScalarFormula)
{
    const auto [isa, hasNormal, hasDepth, sigmaN, spread] = GetParam();
    const afn::cpu::Isa saved = afn::cpu::activeIsa();
    afn::cpu::forceIsa(isa);
    const bool active = afn::cpu::activeIsa() == isa;
    if (active)
        for (const int width : { 37, 101 }) {
            SCOPED_TRACE("width " + std::to_string(width));
            const Scene s = randomScene(hasNormal, hasDepth, sigmaN, width, 3u + width);
            Planes out;
            out.resize(width, kH, kColorPlanes);
            VarianceArgs args;
            args.in = &s.in;
            args.guide = &s.guide;
            args.out = &out;
            args.phiL = kPhiL;
            args.varianceHistory = kVarianceHistory;
            args.spread = spread;
            varianceRows(args, 0, kH);
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < width; ++x) {
                    const Expected e = scalarVariance(s, x, y, spread);
                    for (int k = 0; k < 3; ++k)
                        expectNear(e.rgb[k], out.row(kRed + k, y)[x], "colour", x, y);
                    expectNear(e.variance, out.row(kVariance, y)[x], "variance", x, y);
                    expectNear(e.luminance, out.row(kLuminance, y)[x], "luminance", x, y);
                }
        }
    afn::cpu::forceIsa(saved);
    if (!active)
        GTEST_SKIP() << "this CPU has no " << afn::cpu::isaName(isa);
}

INSTANTIATE_TEST_SUITE_P(GuidesAndExponents, SvgfVarianceKernel,
    ::testing::Combine(::testing::Values(afn::cpu::Isa::Portable, afn::cpu::Isa::Avx512),
        ::testing::Bool(), ::testing::Bool(), ::testing::Values(128.0f, 16.0f, 10.5f),
        ::testing::Bool()));

} // namespace
