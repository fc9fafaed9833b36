// SPDX-License-Identifier: Apache-2.0
// Work skipping (filter/work_mask.h): for every method (one test per method and case),
// the pixels that need denoising come out bit-identical to skip=off on every frame of a sequence
// (static camera, and a camera moving by a sub-pixel step), whatever marks the others (sky depth,
// alpha 0, a user mask); the skipped pixels really take the cheap path where the method has one
// (svgf, bmfr, afn), and nothing changes where it has none; the share is reported; every method's
// "skip" help says which. Plus the mask rules and WorkRegion's dilation.
#include "cpu/isa.h"
#include "filter/work_region.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

using afn::Image;
using afntest::bindImage;
using methods_test::Buffers;
using methods_test::makeImage;

constexpr int kW = 96, kH = 64;
constexpr int kSkyRows = 26; ///< rows 0..25 are sky (about 40 %)

/// Noisy textured geometry below a sky; `frame` varies the noise, (mx, my) the motion vectors.
Buffers scene(int frame, float mx, float my)
{
    Buffers b;
    methods_test::Lcg rng { 17u + 7919u * static_cast<std::uint32_t>(frame) };
    b.albedo = makeImage(
        kW, kH, 3, [](int x, int y, int c) { return 0.3f + 0.2f * (((x / 7) + (y / 5) + c) % 3); });
    b.normal = makeImage(kW, kH, 3, [](int x, int, int c) {
        const float t = 0.3f * std::sin(0.2f * x);
        return c == 0 ? t : c == 1 ? 0.0f : std::sqrt(1.0f - t * t);
    });
    b.depth = makeImage(kW, kH, 1, [](int x, int y, int) {
        if (y < kSkyRows)
            return y % 2 ? std::numeric_limits<float>::infinity() : 1e10f; // both conventions
        return 3.0f + 0.02f * x + (x > 60 ? 1.5f : 0.0f);
    });
    b.position = makeImage(kW, kH, 3, [&](int x, int y, int c) {
        return c == 0 ? 0.05f * x : c == 1 ? 0.05f * y : b.depth(x, y, 0);
    });
    b.motion = makeImage(kW, kH, 2, [&](int, int, int c) { return c == 0 ? mx : my; });
    b.color = makeImage(kW, kH, 3, [&](int x, int y, int c) {
        const float v = y < kSkyRows ? 0.5f + 0.1f * c : b.albedo(x, y, c) * (0.8f + 0.01f * x);
        return std::max(0.0f, v * (1.0f + 0.8f * rng.next()));
    });
    return b;
}

/// Run `frames` frames of method `m` with skip on or off (+ optional alpha and mask images);
/// returns every frame's output.
std::vector<Image> run(const std::string& m, bool skip, int frames, float mx, float my,
    Image* alpha = nullptr, Image* mask = nullptr, double* share = nullptr)
{
    auto f = afn::createFilter(m);
    f->params().setNumber("skip", skip ? 1.0 : 0.0, AFN_PARAM_BOOL);
    std::vector<Image> outs;
    for (int i = 0; i < frames; ++i) {
        Buffers b = scene(i, mx, my);
        if (alpha)
            f->setImage("alpha", bindImage(*alpha));
        if (mask)
            f->setImage("mask", bindImage(*mask));
        methods_test::runFrame(*f, b);
        outs.push_back(b.out);
        if (share)
            *share = f->lastSkippedShare();
    }
    return outs;
}

/// Largest |a - b| over the pixels where need(x, y), and over the others.
void differences(const Image& a, const Image& b, const Image& need, double& needed, double& other)
{
    needed = other = 0.0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = std::fabs(static_cast<double>(a(x, y, c)) - b(x, y, c));
                double& slot = need(x, y, 0) > 0.0f ? needed : other;
                slot = std::isnan(d) ? INFINITY : std::max(slot, d);
            }
}

/// Methods with a cheap path: skipped pixels differ from skip=off. The others (identity, ta:
/// nothing to skip; wskpn, nbgd: not implemented) must come out identical everywhere.
bool skipsWork(const std::string& m)
{
    return m == "svgf" || m == "bmfr" || m == "afn";
}

void expectUnchanged(
    const std::string& m, float mx, float my, Image* alpha, Image* mask, const Image& need)
{
    double share = 0.0;
    const std::vector<Image> on = run(m, true, 6, mx, my, alpha, mask, &share);
    const std::vector<Image> off = run(m, false, 6, mx, my, alpha, mask);
    EXPECT_GT(share, 0.3) << m;
    double otherMax = 0.0;
    for (std::size_t i = 0; i < on.size(); ++i) {
        double needed = 0.0, other = 0.0;
        differences(on[i], off[i], need, needed, other);
        EXPECT_EQ(needed, 0.0) << m << " frame " << i << " motion " << mx << "," << my;
        otherMax = std::max(otherMax, other);
    }
    // Where a method skips, the skipped pixels must differ somewhere (else nothing was skipped
    // and the test above proves nothing); where it does not, skip must change nothing.
    if (skipsWork(m))
        EXPECT_GT(otherMax, 0.0) << m;
    else
        EXPECT_EQ(otherMax, 0.0) << m;
}

Image belowSky()
{
    return makeImage(kW, kH, 1, [](int, int y, int) { return y >= kSkyRows ? 1.0f : 0.0f; });
}

/// Every registered method that runs as created (afn, wskpn, nbgd: builds with their weights).
std::vector<std::string> readyMethods()
{
    std::vector<std::string> names;
    for (const afn::FilterType& t : afn::filterTypes())
        if (t.ready)
            names.push_back(t.name);
    return names;
}

class WorkSkipping : public testing::TestWithParam<std::string> { };

} // namespace

TEST_P(WorkSkipping, SkyPixelsSkippedOthersBitIdenticalStaticCamera)
{
    expectUnchanged(GetParam(), 0.0f, 0.0f, nullptr, nullptr, belowSky());
}

TEST_P(WorkSkipping, SkyPixelsSkippedOthersBitIdenticalSubPixelMotion)
{
    expectUnchanged(GetParam(), 0.3f, -0.2f, nullptr, nullptr, belowSky());
}

TEST_P(WorkSkipping, AlphaAndUserMaskSkippedOthersBitIdentical)
{
    // Alpha 0 on the left 20 columns, a user mask that leaves out the right 30 columns.
    Image alpha = makeImage(kW, kH, 1, [](int x, int, int) { return x < 20 ? 0.0f : 1.0f; });
    Image mask = makeImage(kW, kH, 1, [](int x, int, int) { return x < kW - 30 ? 1.0f : 0.0f; });
    const Image need = makeImage(kW, kH, 1,
        [](int x, int y, int) { return y >= kSkyRows && x >= 20 && x < kW - 30 ? 1.0f : 0.0f; });
    expectUnchanged(GetParam(), 0.0f, 0.0f, &alpha, &mask, need);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, WorkSkipping, testing::ValuesIn(readyMethods()),
    [](const testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(WorkSkippingSvgf, BothAtrousKernelsKeepNeededPixelsBitIdentical)
{
    // The portable 8-lane and the AVX-512 16-lane à-trous kernels each restrict their rows to
    // the region; each must keep the needed pixels of its own skip=off run (where the CPU has
    // no AVX-512 both runs are the portable kernel).
    const afn::cpu::Isa saved = afn::cpu::activeIsa();
    std::vector<Image> byIsa[2];
    int k = 0;
    for (afn::cpu::Isa isa : { afn::cpu::Isa::Portable, afn::cpu::Isa::Avx512 }) {
        afn::cpu::forceIsa(isa);
        expectUnchanged("svgf", 0.3f, -0.2f, nullptr, nullptr, belowSky());
        byIsa[k++] = run("svgf", true, 3, 0.3f, -0.2f);
    }
    afn::cpu::forceIsa(saved);
    // And the two kernels agree within the tolerance the kernels have without skipping
    // (methods/svgf/kernels.h: max relative difference 1.1e-5 on examples/sequence).
    const Image need = belowSky();
    for (std::size_t f = 0; f < byIsa[0].size(); ++f)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c)
                    if (need(x, y, 0) > 0.0f) {
                        const float a = byIsa[0][f](x, y, c), b = byIsa[1][f](x, y, c);
                        EXPECT_LE(std::fabs(a - b), 1e-4f * std::max(1.0f, std::fabs(a)))
                            << x << "," << y << " frame " << f;
                    }
}

TEST(WorkSkippingSvgf, WithTaaNothingIsSkippedAndSkipChangesNoPixel)
{
    // svgf's TAA (taa=1) samples history across the region's edge, so svgf then filters every
    // pixel (methods/svgf/work_skip.cpp): skip on and off give the same bits everywhere, with
    // camera motion; the TAA changed the output (it is not the taa=0 result).
    auto runTaa = [](bool skip, bool taa) {
        auto f = afn::createFilter("svgf");
        f->params().setNumber("skip", skip ? 1.0 : 0.0, AFN_PARAM_BOOL);
        f->params().setNumber("taa", taa ? 1.0 : 0.0, AFN_PARAM_BOOL);
        std::vector<Image> outs;
        for (int i = 0; i < 5; ++i) {
            Buffers b = scene(i, 0.3f, -0.2f);
            methods_test::runFrame(*f, b);
            outs.push_back(b.out);
        }
        return outs;
    };
    const std::vector<Image> on = runTaa(true, true), off = runTaa(false, true);
    const std::vector<Image> plain = runTaa(false, false);
    const Image everywhere(kW, kH, 1, 1.0f);
    double changedByTaa = 0.0;
    for (std::size_t i = 0; i < on.size(); ++i) {
        double needed = 0.0, other = 0.0;
        differences(on[i], off[i], everywhere, needed, other);
        EXPECT_EQ(needed, 0.0) << "frame " << i;
        differences(off[i], plain[i], everywhere, needed, other);
        changedByTaa = std::max(changedByTaa, needed);
    }
    EXPECT_GT(changedByTaa, 1e-3);
}

TEST(WorkSkippingHelp, EveryMethodSaysWhatSkipDoes)
{
    // The help of "skip" states the method's behaviour; the ones that skip nothing say so.
    for (const afn::FilterType& t : afn::filterTypes()) {
        std::string help;
        for (const afn::ParamDesc& d : t.params)
            if (d.name == "skip")
                help = d.help;
        EXPECT_NE(help.find("In this method: "), std::string::npos) << t.name;
        const bool says = help.find("not implemented") != std::string::npos
            || help.find("nothing to skip") != std::string::npos;
        EXPECT_EQ(says, !skipsWork(t.name)) << t.name << ": " << help;
    }
}

TEST(WorkSkipping, MaskRulesAndShare)
{
    // Sky rows: share = kSkyRows / kH. A NaN mask is "not needed"; skip=off builds no mask.
    double share = 0.0;
    run("ta", true, 1, 0.0f, 0.0f, nullptr, nullptr, &share);
    EXPECT_DOUBLE_EQ(share, static_cast<double>(kSkyRows) / kH);
    Image mask = makeImage(kW, kH, 1,
        [](int x, int, int) { return x == 0 ? std::numeric_limits<float>::quiet_NaN() : 1.0f; });
    run("ta", true, 1, 0.0f, 0.0f, nullptr, &mask, &share);
    EXPECT_DOUBLE_EQ(share, (kSkyRows * kW + (kH - kSkyRows)) / static_cast<double>(kW * kH));
    run("ta", false, 1, 0.0f, 0.0f, nullptr, &mask, &share);
    EXPECT_EQ(share, 0.0);
    // A range below the scene's depth (3..6) skips everything.
    auto f = afn::createFilter("ta");
    f->params().setNumber("denoisingRange", 2.0, AFN_PARAM_FLOAT);
    Buffers b = scene(0, 0.0f, 0.0f);
    methods_test::runFrame(*f, b);
    EXPECT_EQ(f->lastSkippedShare(), 1.0);
}

TEST(WorkSkipping, OneBackgroundDepthAnywhereIsFound)
{
    // A frame whose pixels all need work except one, whose depth is each kind of background in
    // turn: the row check that looks for such a pixel before the mask is built (a vectorised run
    // over a packed depth row) finds it at every position of a 16-value block and in the tail.
    const float inf = std::numeric_limits<float>::infinity();
    const float range = 100.0f;
    for (float z : { std::numeric_limits<float>::quiet_NaN(), inf, -inf, range, 2.0f * range })
        for (int x : { 0, 5, 15, 16, 47, 80, kW - 1 }) {
            auto f = afn::createFilter("ta");
            f->params().setNumber("denoisingRange", range, AFN_PARAM_FLOAT);
            Buffers b = scene(0, 0.0f, 0.0f);
            b.depth = Image(kW, kH, 1, 3.0f);
            b.depth(x, 40, 0) = z;
            methods_test::runFrame(*f, b);
            EXPECT_EQ(f->lastSkippedShare(), 1.0 / (kW * kH)) << "depth " << z << " at x " << x;
        }
    // Just below the range, -FLT_MAX and -0 need work: nothing is skipped.
    for (float z : { std::nextafter(range, 0.0f), -std::numeric_limits<float>::max(), -0.0f }) {
        auto f = afn::createFilter("ta");
        f->params().setNumber("denoisingRange", range, AFN_PARAM_FLOAT);
        Buffers b = scene(0, 0.0f, 0.0f);
        b.depth = Image(kW, kH, 1, 3.0f);
        b.depth(33, 40, 0) = z;
        methods_test::runFrame(*f, b);
        EXPECT_EQ(f->lastSkippedShare(), 0.0) << "depth " << z;
    }
}

TEST(WorkRegion, SpansDilationAndIntersection)
{
    Image work(20, 10, 1);
    work(5, 4, 0) = 1.0f;
    work(9, 4, 0) = 1.0f;
    const afn::WorkRegion r = afn::WorkRegion::fromMask(work);
    EXPECT_EQ(r.x0(4), 5);
    EXPECT_EQ(r.x1(4), 10);
    EXPECT_TRUE(r.rowEmpty(3));
    EXPECT_EQ(r.area(), 5);
    const afn::WorkRegion d = r.dilated(2);
    for (int y = 0; y < 10; ++y) {
        const bool inside = y >= 2 && y <= 6;
        EXPECT_EQ(d.rowEmpty(y), !inside) << y;
        if (inside) {
            EXPECT_EQ(d.x0(y), 3);
            EXPECT_EQ(d.x1(y), 12);
        }
    }
    EXPECT_TRUE(d.intersects(11, 6, 15, 9));
    EXPECT_FALSE(d.intersects(12, 0, 20, 10));
    EXPECT_FALSE(d.intersects(0, 7, 20, 10));
    const afn::WorkRegion clipped = r.dilated(30);
    EXPECT_EQ(clipped.x0(0), 0);
    EXPECT_EQ(clipped.x1(9), 20);
    EXPECT_EQ(clipped.area(), 200);
}
