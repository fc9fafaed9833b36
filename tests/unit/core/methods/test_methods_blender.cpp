// SPDX-License-Identifier: Apache-2.0
// ta, svgf and bmfr on the bundled Blender sequence (examples/sequence: 8 frames, 320x180, 1 spp,
// 2048-spp references): each must clearly beat the noisy input in PSNR. The EXRs are read with
// OpenImageIO directly (blender_frames.h), independent of afn_io. PSNR as the reference notes
// define it: tone map T(x) = clip(max(x, 0)^(1/2.2), 0, 1), 10 log10(1 / MSE).
// Reproduce the per-frame table: test_methods --gtest_filter='*Blender*'
#include "blender_frames.h"
#include "test_methods_util.h"

#include <map>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using afn::Image;

constexpr int kFrames = 8;

double psnr(const Image& a, const Image& ref)
{
    auto t = [](float x) { return std::fmin(1.0, std::pow(std::fmax(x, 0.0f), 1.0 / 2.2)); };
    double se = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = t(a.data()[i]) - t(ref.data()[i]);
        se += d * d;
    }
    return 10.0 * std::log10(static_cast<double>(a.size()) / se);
}

TEST(MethodsBlender, EveryMethodClearlyBeatsTheNoisyInput)
{
    std::vector<methods_test::Buffers> frames(kFrames);
    std::vector<Image> refs(kFrames);
    for (int k = 0; k < kFrames; ++k) {
        afntest::BlenderFrame f = afntest::readBlenderFrame(AFN_EXAMPLES_DIR, k);
        if (f.color.empty())
            GTEST_SKIP() << "cannot read frame " << k << " of " << AFN_EXAMPLES_DIR;
        methods_test::Buffers& b = frames[k];
        b.color = f.color;
        b.albedo = f.albedo;
        b.normal = f.normal;
        b.depth = f.depth;
        b.position = f.position;
        b.motion = f.motion;
        refs[k] = f.reference;
        ASSERT_FALSE(refs[k].empty() || b.albedo.empty() || b.motion.empty()) << "frame " << k;
    }
    double noisyMean = 0.0;
    for (int k = 0; k < kFrames; ++k)
        noisyMean += psnr(frames[k].color, refs[k]) / kFrames;
    std::printf("%-6s mean %6.2f dB (noisy 1 spp input)\n", "input", noisyMean);
    std::vector<std::string> methods = { "ta", "svgf", "bmfr" };
    if (afn::findFilterType("afn")->ready)
        methods.push_back("afn"); // the shipped model (its training never saw this scene)
    std::map<std::string, double> means;
    for (const std::string& m : methods) {
        auto f = afn::createFilter(m);
        f->params().setNumber("motion.yUp", 1.0, AFN_PARAM_BOOL);
        double mean = 0.0;
        std::string row;
        for (int k = 0; k < kFrames; ++k) {
            methods_test::Buffers b = frames[k];
            methods_test::runFrame(*f, b);
            ASSERT_TRUE(methods_test::allFiniteNonNegative(b.out)) << m;
            const double p = psnr(b.out, refs[k]);
            mean += p / kFrames;
            row += " " + std::to_string(p).substr(0, 5);
        }
        std::printf("%-6s mean %6.2f dB, per frame:%s\n", m.c_str(), mean, row.c_str());
        // Observed: ta +6, svgf +12, bmfr +9 dB; "clearly" = at least 5 dB on average.
        EXPECT_GT(mean, noisyMean + 5.0) << m;
        means[m] = mean;
    }
    if (means.count("afn")) {
        // The shipped network must do what it is for: far above the input and above its own
        // TA-1spp input (observed with the shipped weights: input + 12 dB, TA + 6 dB).
        EXPECT_GT(means["afn"], noisyMean + 10.0);
        EXPECT_GT(means["afn"], means["ta"] + 3.0);
    }
}

} // namespace
