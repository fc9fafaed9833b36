// SPDX-License-Identifier: Apache-2.0
// The core's Reprojector + TemporalAccumulator against golden vectors made by an independent
// numpy implementation of BMFR's accumulation (tests/data/afn_parity/ta_case.afnw: sub-pixel
// motion, off-screen taps, position and normal rejections). Both compute in float32 in the same
// order, so they must agree exactly. (The training toolkit now prepares its inputs through the core
// itself, afntool --features.)
#include "afn_test_util.h"
#include "filter/frame.h"
#include "stages/reproject.h"
#include "stages/temporal_accumulation.h"

#include <gtest/gtest.h>

#include <cmath>

TEST(AfnTaParity, PythonTaEqualsCoreTa)
{
    const auto c = afntest::loadFile(std::string(AFN_TEST_DATA) + "/afn_parity/ta_case.afnw");
    afn::Reprojector reproject;
    afn::TemporalAccumulator ta;
    for (int f = 0; f < 3; ++f) {
        const std::string s = std::to_string(f);
        afn::Frame frame;
        const afn::Image irr = afntest::toImage(c.tensor("irr_" + s));
        frame.width = irr.width();
        frame.height = irr.height();
        frame.motion = afntest::toImage(c.tensor("motion_" + s));
        frame.position = afntest::toImage(c.tensor("position_" + s));
        frame.normal = afntest::toImage(c.tensor("normal_" + s));
        frame.frameIndex = f;
        reproject.compute(frame);
        ta.accumulate(reproject, irr);
        reproject.storeGeometry(frame);
        const afn::Image acc = afntest::toImage(c.tensor("acc_" + s));
        const afn::Image spp = afntest::toImage(c.tensor("spp_" + s));
        int differ = 0, resets = 0;
        double maxDiff = 0;
        for (std::size_t k = 0; k < acc.size(); ++k) {
            const float a = ta.color().data()[k], b = acc.data()[k];
            differ += a != b;
            maxDiff = std::max(maxDiff, static_cast<double>(std::fabs(a - b)));
        }
        for (std::size_t k = 0; k < spp.size(); ++k) {
            EXPECT_EQ(ta.historyLength().data()[k], spp.data()[k])
                << "frame " << f << " pixel " << k;
            resets += spp.data()[k] == 1.0f;
        }
        EXPECT_EQ(differ, 0) << "frame " << f << ": max difference " << maxDiff;
        if (f > 0) {
            // the case exercises both accepted and rejected history
            EXPECT_GT(resets, 0) << f;
            EXPECT_LT(resets, static_cast<int>(spp.size())) << f;
        }
    }
}
