// SPDX-License-Identifier: Apache-2.0
// SVGF's vectorised row kernels (methods/svgf/kernels.h) against a plain scalar evaluation of the
// documented formulas (methods/svgf/guide.h, kernels.h), in double precision, on random planes:
// both kernel families (portable 8 lanes, AVX-512 16 lanes where the CPU has it), every guide
// combination (normal and/or depth or neither), steps 1 to 32 (beyond the planes' padding
// included), widths that are not a multiple of the vector width: 37, and 101, where every step up
// to 16 has blocks whose taps all lie inside the image (the AVX-512 kernel's unmasked path). A
// kernel that reads the wrong plane, offset or weight (as a depth tap reading the normals' y once
// did, or a mirrored tap taking its partner's column mask) fails here even where the method-level
// tests still see a plausible image.
#include "cpu/isa.h"
#include "methods/svgf/kernels.h"
#include "svgf_random_guide.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace afn::svgf;

constexpr int kW = 37, kH = 23; // not multiples of the 8 lanes; step 16 leaves the padded row
constexpr int kWide = 101; // blocks at x = 32 and 48 have all taps of step 16 inside

constexpr float kSigmaL = 4.0f;

struct Scene {
    Planes in;
    Guide guide;
};

Scene randomScene(bool hasNormal, bool hasDepth, unsigned seed, int width = kW)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Scene s;
    s.in.resize(width, kH, kColorPlanes);
    s.guide.planes.resize(width, kH, kGuidePlanes);
    s.guide.hasNormal = hasNormal;
    s.guide.hasDepth = hasDepth;
    s.guide.sigmaZ = 1.0f;
    s.guide.sigmaN = 16.0f; // a power of two, as the default 128, with fewer vanishing weights
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < width; ++x) {
            float c[3];
            for (int k = 0; k < 3; ++k)
                s.in.row(k, y)[x] = c[k] = 2.0f * u(rng);
            s.in.row(kVariance, y)[x] = 0.5f * u(rng);
            s.in.row(kLuminance, y)[x] = luminance(c);
            afntest::setRandomGuidePixel(s.guide, x, y, 0.3f, rng);
        }
    return s;
}

float plane(const Planes& p, int k, int x, int y)
{
    return p.row(k, y)[x];
}

/// invPhiL of pixel (x, y): 1 / (sigmaL sqrt(g3x3(variance)) + 1e-10), the 3x3 Gaussian
/// renormalised over in-image taps.
double scalarInvPhi(const Scene& s, int x, int y)
{
    const int width = s.in.width();
    const double g[3] = { 0.25, 0.5, 0.25 }; // per axis
    double sum = 0.0, wsum = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qx >= width || qy < 0 || qy >= kH)
                continue;
            const double w = g[dx + 1] * g[dy + 1];
            sum += w * plane(s.in, kVariance, qx, qy);
            wsum += w;
        }
    return 1.0 / (kSigmaL * std::sqrt(std::max(0.0, sum / wsum)) + 1e-10);
}

/// One output pixel of the à-trous iteration, evaluated literally.
struct Expected {
    double rgb[3], variance, luminance;
};

Expected scalarAtrous(const Scene& s, int step, int x, int y)
{
    const int width = s.in.width();
    const double b3[3] = { 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0 };
    const Guide& g = s.guide;
    double cp[3];
    for (int k = 0; k < 3; ++k)
        cp[k] = plane(s.in, k, x, y);
    const double lp = plane(s.in, kLuminance, x, y), invPhi = scalarInvPhi(s, x, y);
    double ws = 0.0, vsum = 0.0, dc[3] = {};
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            const int qx = x + i * step, qy = y + j * step;
            if (qx < 0 || qx >= width || qy < 0 || qy >= kH)
                continue;
            const double h = b3[std::abs(i)] * b3[std::abs(j)];
            double w = h;
            if (i != 0 || j != 0) {
                const afntest::GuideTerms t
                    = afntest::scalarGuideTerms(g, x, y, qx, qy, i * step, j * step);
                const double e = std::abs(lp - plane(s.in, kLuminance, qx, qy)) * invPhi + t.depth;
                w = h * std::exp(-e) * t.normal;
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

/// Select a kernel family for the life of the object (the CPU's own choice afterwards).
class UseIsa {
public:
    explicit UseIsa(afn::cpu::Isa isa)
        : m_saved(afn::cpu::activeIsa())
    {
        afn::cpu::forceIsa(isa);
    }
    ~UseIsa() { afn::cpu::forceIsa(m_saved); }
    bool active(afn::cpu::Isa isa) const { return afn::cpu::activeIsa() == isa; }

private:
    afn::cpu::Isa m_saved;
};

class SvgfAtrousKernel
    : public ::testing::TestWithParam<std::tuple<afn::cpu::Isa, bool, bool, int>> { };

TEST_P(SvgfAtrousKernel, MatchesTheScalarFormula)
{
    const auto [isa, hasNormal, hasDepth, step] = GetParam();
    const UseIsa use(isa);
    if (!use.active(isa))
        GTEST_SKIP() << "this CPU has no " << afn::cpu::isaName(isa);
    for (const int width : { kW, kWide }) {
        SCOPED_TRACE("width " + std::to_string(width));
        const Scene s = randomScene(hasNormal, hasDepth, 7u + step, width);
        Planes out;
        out.resize(width, kH, kColorPlanes);
        const AtrousArgs args { &s.in, kSigmaL, &s.guide, &out, step };
        atrousRows(args, 0, kH);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < width; ++x) {
                const Expected e = scalarAtrous(s, step, x, y);
                for (int k = 0; k < 3; ++k)
                    expectNear(e.rgb[k], plane(out, k, x, y), "colour", x, y);
                expectNear(e.variance, plane(out, kVariance, x, y), "variance", x, y);
                expectNear(e.luminance, plane(out, kLuminance, x, y), "luminance", x, y);
            }
    }
}

// The rows in any order and any split give the same bits (Denoiser::atrous orders them by y mod
// step; the thread count decides the split).
TEST_P(SvgfAtrousKernel, RowOrderAndSplitLeaveTheResultUnchanged)
{
    const auto [isa, hasNormal, hasDepth, step] = GetParam();
    const UseIsa use(isa);
    if (!use.active(isa))
        GTEST_SKIP() << "this CPU has no " << afn::cpu::isaName(isa);
    const Scene s = randomScene(hasNormal, hasDepth, 11u + step);
    Planes plain, ordered;
    plain.resize(kW, kH, kColorPlanes);
    ordered.resize(kW, kH, kColorPlanes);
    atrousRows({ &s.in, kSigmaL, &s.guide, &plain, step }, 0, kH);
    std::vector<int> order;
    for (int r = 0; r < step; ++r)
        for (int y = r; y < kH; y += step)
            order.push_back(y);
    std::reverse(order.begin(), order.end());
    const AtrousArgs args { &s.in, kSigmaL, &s.guide, &ordered, step, order.data() };
    atrousRows(args, kH / 3, kH);
    atrousRows(args, 0, kH / 3);
    for (int k = 0; k < kColorPlanes; ++k)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_EQ(plane(plain, k, x, y), plane(ordered, k, x, y))
                    << "plane " << k << " at (" << x << ", " << y << ")";
}

INSTANTIATE_TEST_SUITE_P(GuidesAndSteps, SvgfAtrousKernel,
    ::testing::Combine(::testing::Values(afn::cpu::Isa::Portable, afn::cpu::Isa::Avx512),
        ::testing::Bool(), ::testing::Bool(), ::testing::Values(1, 2, 4, 8, 16, 32)));

} // namespace
