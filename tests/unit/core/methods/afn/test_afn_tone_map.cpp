// SPDX-License-Identifier: Apache-2.0
// The AFN input tone map without powf (methods/afn/tone_map.h): against std::pow within 3e-7
// absolute and 4 ulp on a sweep of (0, 1) (every 97th float, denormals included), exact at the
// clip points, and the AVX-512 run gives the scalar function's bits (on a CPU without AVX-512F
// both take the scalar path, said in the output). The bf16 network's tone map (toneMapRunBf16)
// within 1e-5 relative of it over the same sweep, with the same limits and special values.
#include "cpu/isa.h"
#include "isa_scope.h"
#include "methods/afn/tone_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <vector>

namespace {

using afn::afnet::toneMap;
using afn::afnet::toneMapRun;
using afn::afnet::toneMapRunBf16;

float fromBits(std::uint32_t b)
{
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
}

std::uint32_t bitsOf(float f)
{
    std::uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

/// Every 97th positive float below 1 (denormals first), about 11 million values.
std::vector<float> sweep()
{
    std::vector<float> v;
    for (std::uint32_t b = 1; b < bitsOf(1.0f); b += 97)
        v.push_back(fromBits(b));
    return v;
}

TEST(AfnToneMap, CloseToPowOverTheUnitInterval)
{
    double maxAbs = 0.0, maxUlp = 0.0;
    float worst = 0.0f;
    for (float x : sweep()) {
        const float ref = static_cast<float>(std::pow(static_cast<double>(x), 1.0 / 2.2));
        const float got = toneMap(x);
        const double d = std::fabs(static_cast<double>(got) - ref);
        const double ulp = d / (std::nextafter(ref, 2.0f) - ref);
        if (d > maxAbs)
            maxAbs = d, worst = x;
        maxUlp = std::max(maxUlp, ulp);
    }
    std::cout << "[ info ] max |toneMap - pow| = " << maxAbs << " (at " << worst << "), " << maxUlp
              << " ulp\n";
    EXPECT_LE(maxAbs, 3e-7);
    EXPECT_LE(maxUlp, 4.0);
}

TEST(AfnToneMap, ClipsAndSpecialValues)
{
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(toneMap(0.0f), 0.0f);
    EXPECT_EQ(toneMap(-0.0f), 0.0f);
    EXPECT_EQ(toneMap(-3.0f), 0.0f);
    EXPECT_EQ(toneMap(-inf), 0.0f);
    EXPECT_EQ(toneMap(std::numeric_limits<float>::quiet_NaN()), 0.0f);
    EXPECT_EQ(toneMap(1.0f), 1.0f);
    EXPECT_EQ(toneMap(7.5f), 1.0f);
    EXPECT_EQ(toneMap(inf), 1.0f);
    EXPECT_LT(toneMap(std::nextafter(1.0f, 0.0f)), 1.0f + 1e-7f);
    EXPECT_GT(toneMap(std::numeric_limits<float>::denorm_min()), 0.0f);
    // Monotone on a fine grid.
    float prev = 0.0f;
    for (int i = 1; i <= 100000; ++i) {
        const float v = toneMap(i / 100000.0f);
        EXPECT_GE(v, prev) << i;
        prev = v;
    }
}

TEST(AfnToneMap, VectorRunGivesTheScalarBits)
{
    if (!isa_test::haveAvx512())
        std::cout << "[ info ] this CPU has no AVX-512F: both runs take the scalar path\n";
    std::vector<float> in = sweep();
    const float inf = std::numeric_limits<float>::infinity();
    for (float s : { 0.0f, -0.0f, -1.0f, 1.0f, 2.0f, inf, -inf,
             std::numeric_limits<float>::quiet_NaN(), 0.5f })
        in.push_back(s);
    in.push_back(0.25f); // a tail that is not a multiple of 16
    std::vector<float> out(in.size());
    {
        const isa_test::IsaScope scope(afn::cpu::Isa::Avx512);
        toneMapRun(in.data(), out.data(), static_cast<int>(in.size()));
    }
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < in.size(); ++i)
        if (bitsOf(out[i]) != bitsOf(toneMap(in[i])) && ++mismatches < 5)
            ADD_FAILURE() << "x = " << in[i] << ": run " << out[i] << " vs scalar "
                          << toneMap(in[i]);
    EXPECT_EQ(mismatches, 0u);
}

TEST(AfnToneMap, Bf16InputsRunWithinItsToleranceAndTheSameLimits)
{
    if (!isa_test::haveAvx512())
        std::cout << "[ info ] this CPU has no AVX-512F: toneMapRunBf16 takes the scalar path\n";
    std::vector<float> in = sweep();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> special
        = { 0.0f, -0.0f, -1.0f, 1.0f, 2.0f, inf, -inf, std::numeric_limits<float>::quiet_NaN(),
              std::numeric_limits<float>::denorm_min(), std::nextafter(1.0f, 0.0f), 0.5f, 0.25f };
    in.insert(in.end(), special.begin(), special.end());
    in.push_back(0.125f); // a tail that is not a multiple of 16
    std::vector<float> out(in.size());
    {
        const isa_test::IsaScope scope(afn::cpu::Isa::Avx512);
        toneMapRunBf16(in.data(), out.data(), static_cast<int>(in.size()));
    }
    double maxRel = 0.0;
    float worst = 0.0f;
    bool differs = false;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const float want = toneMap(in[i]);
        differs = differs || bitsOf(out[i]) != bitsOf(want);
        if (want == 0.0f || want == 1.0f) { // the limits: exactly
            ASSERT_EQ(out[i], want) << "x = " << in[i];
            continue;
        }
        const double rel = std::fabs(static_cast<double>(out[i]) - want) / want;
        if (rel > maxRel)
            maxRel = rel, worst = in[i];
    }
    std::cout << "[ info ] max |toneMapRunBf16 / toneMap - 1| = " << maxRel << " (at " << worst
              << ")\n";
    EXPECT_LT(maxRel, 1e-5);
    if (isa_test::haveAvx512())
        EXPECT_TRUE(differs) << "the cheaper tone map did not run";
}

} // namespace
