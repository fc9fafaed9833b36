// SPDX-License-Identifier: Apache-2.0
// The "afn" filter type: refuses to run without weights, takes weights as data (rejecting corrupt
// ones without losing the previous), denoises a small sequence; feature scaling hand cases; the
// network's precision (auto/fp32/bf16) as chosen and reported.
#include "afn_test_util.h"
#include "base/exception.h"
#include "cpu/isa.h"
#include "filter/registry.h"
#include "isa_scope.h"
#include "stages/aux_prefilter.h"
#include "stages/feature_scaling.h"
#include "still_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

using afntest::readBytes;

TEST(AfnFilter, NeedsWeightsThenDenoises)
{
    auto f = afn::createFilter("afn");
    const int w = 19, h = 11;
    afntest::StillFrame still(w, h);
    still.bindTo(*f);
    still.bindMotionTo(*f); // weights_full.afnw is a full-input-set model
    const afn::Image& out = still.out;
#ifndef AFN_HAS_EMBEDDED_WEIGHTS
    try {
        f->commit();
        FAIL() << "commit without weights must fail";
    } catch (const afn::Exception& e) {
        EXPECT_NE(std::string(e.what()).find("no weights"), std::string::npos) << e.what();
    }
#endif
    EXPECT_THROW(f->setData("weights", "garbage", 7), afn::Exception);
    EXPECT_THROW(f->setData("other", "x", 1), afn::Exception);
    const auto bytes = readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw");
    f->setData("weights", bytes.data(), bytes.size());
    EXPECT_THROW(
        f->setData("weights", bytes.data(), bytes.size() / 2), afn::Exception); // truncated
    f->commit(); // the valid weights survived the failed replacement
    for (int frame = 0; frame < 3; ++frame) {
        f->execute();
        for (std::size_t k = 0; k < out.size(); ++k) {
            ASSERT_TRUE(std::isfinite(out.data()[k]));
            ASSERT_GE(out.data()[k], 0.0f);
        }
    }
}

TEST(AfnFeatures, NormalAndDepthScaling)
{
    afn::Image n(2, 1, 3), n01;
    n(0, 0, 0) = -1.0f;
    n(0, 0, 1) = 1.0f;
    n(1, 0, 2) = NAN;
    afn::normalToUnitRange(n, 2, 1, n01);
    EXPECT_EQ(n01(0, 0, 0), 0.0f);
    EXPECT_EQ(n01(0, 0, 1), 1.0f);
    EXPECT_EQ(n01(0, 0, 2), 0.5f);
    EXPECT_EQ(n01(1, 0, 2), 0.5f);
    afn::Image z(4, 1, 1), z01;
    z(0, 0, 0) = 2.0f;
    z(1, 0, 0) = 4.0f;
    z(2, 0, 0) = 6.0f;
    z(3, 0, 0) = 1e10f; // sky
    afn::depthToUnitRange(z, 4, 1, z01);
    EXPECT_EQ(z01(0, 0, 0), 0.0f);
    EXPECT_EQ(z01(1, 0, 0), 0.5f);
    EXPECT_EQ(z01(2, 0, 0), 1.0f);
    EXPECT_EQ(z01(3, 0, 0), 1.0f);
    afn::depthToUnitRange(afn::Image(), 3, 2, z01);
    EXPECT_EQ(z01.width(), 3);
    EXPECT_EQ(z01(2, 1, 0), 0.0f);
}

TEST(AfnFilter, SampleCountParameter)
{
    const afn::FilterType* t = afn::findFilterType("afn");
    ASSERT_NE(t, nullptr);
    const auto it = std::find_if(t->params.begin(), t->params.end(),
        [](const afn::ParamDesc& d) { return d.name == "spp"; });
    ASSERT_NE(it, t->params.end());
    EXPECT_EQ(it->type, AFN_PARAM_INT);
    EXPECT_EQ(it->defaultValue, 0.0); // unknown until the host reads the file
    afn::ParamSet params(&t->params);
    EXPECT_EQ(afn::auxBinding().read(params).spp, 0);
    params.setNumber("spp", 64, AFN_PARAM_INT);
    EXPECT_EQ(afn::auxBinding().read(params).spp, 64);
    EXPECT_THROW(params.setNumber("spp", -1, AFN_PARAM_INT), afn::Exception);
}

namespace {

/// The last frame's AFN_STAT_AFN_PRECISION of an afn filter with precision `p` on a small still.
double precisionRan(const std::string& p, std::vector<float>* out = nullptr, double* amx = nullptr)
{
    auto f = afn::createFilter("afn");
    afntest::StillFrame still(21, 13);
    still.bindTo(*f);
    still.bindMotionTo(*f);
    const auto bytes = readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw");
    f->setData("weights", bytes.data(), bytes.size());
    f->params().setString("precision", p);
    f->commit();
    f->execute();
    f->execute();
    if (out)
        out->assign(still.out.data(), still.out.data() + still.out.size());
    double v = 0;
    EXPECT_TRUE(f->statistic(AFN_STAT_AFN_PRECISION, v));
    if (amx)
        EXPECT_TRUE(f->statistic(AFN_STAT_AFN_BF16_AMX, *amx));
    return v;
}

} // namespace

TEST(AfnFilter, PrecisionIsChosenFromTheCpuAndReported)
{
    std::vector<float> fp32, bf16;
    EXPECT_EQ(precisionRan("fp32", &fp32), 32.0);
    if (afn::cpu::activeIsa() != afn::cpu::Isa::Avx512) {
        EXPECT_EQ(precisionRan("auto"), 32.0);
        EXPECT_THROW(precisionRan("bf16"), afn::Exception); // needs the AVX-512 engine
        return;
    }
    EXPECT_EQ(precisionRan("bf16", &bf16), 16.0);
    double amx = -1;
    EXPECT_EQ(precisionRan("auto", nullptr, &amx), afn::cpu::cpuHasAvx512Bf16() ? 16.0 : 32.0);
    // AMX tiles where the CPU and the OS allow them (cpu/isa.h), reported as such.
    EXPECT_EQ(amx, afn::cpu::activeBf16Mode() == afn::cpu::Bf16Mode::Amx ? 1.0 : 0.0);
    if (!std::getenv("AFN_CPU_BF16")) // AFN_CPU_BF16=avx512|emulate overrides the choice
        EXPECT_EQ(afn::cpu::activeBf16Mode() == afn::cpu::Bf16Mode::Amx, afn::cpu::cpuHasAmxBf16());
    // Close to fp32 but not the same: the convolutions did run in bf16.
    double worst = 0;
    bool differs = false;
    for (std::size_t k = 0; k < fp32.size(); ++k) {
        worst = std::max(worst, std::fabs(double(fp32[k]) - bf16[k]) / std::max(1.0f, fp32[k]));
        differs |= fp32[k] != bf16[k];
    }
    EXPECT_TRUE(differs);
    EXPECT_LT(worst, 0.05);
    // Without the AVX-512 engine bf16 is refused at commit, auto falls back to fp32.
    const isa_test::IsaScope portable(afn::cpu::Isa::Portable);
    EXPECT_THROW(precisionRan("bf16"), afn::Exception);
    EXPECT_EQ(precisionRan("auto"), 32.0);
    EXPECT_THROW(precisionRan("fp16"), afn::Exception); // not a choice
}
