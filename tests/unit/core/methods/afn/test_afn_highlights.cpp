// SPDX-License-Identifier: Apache-2.0
// afn's highlight bypass (stages/highlight_bypass.h, parameter "highlights"): a single pixel far
// brighter than the frame (a small lamp hit by a 1-spp sample) stays at its pixel instead of
// spreading into a blotch, with its energy; a frame with nothing that bright is denoised bit for
// bit as with the bypass off; the pixels kept are reported (AFN_STAT_HIGHLIGHTS through
// Filter::lastHighlightPixels).
#include "afn_synthetic_sequence.h"
#include "afn_test_util.h"
#include "filter/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using afn::Image;
using afntest::SequenceFrame;

constexpr int kW = 48, kH = 32;
constexpr int kX = 23, kY = 15; ///< the bright pixel
constexpr float kBright = 1e4f;

std::unique_ptr<afn::Filter> afnFilter(double highlights)
{
    auto f = afn::createFilter("afn");
    f->params().setNumber("highlights", highlights, AFN_PARAM_FLOAT);
    // The committed parity weights: variant full, 1 spp (TAA and post-filter on under auto).
    const auto w = afntest::readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw");
    f->setData(AFN_DATA_WEIGHTS, w.data(), w.size());
    return f;
}

/// Frame 0 of the synthetic scene, optionally with one bright pixel.
Image run(double highlights, bool bright, double* kept = nullptr)
{
    const afntest::SyntheticSequence seq(kW, kH, 3);
    SequenceFrame f = seq.frame(0, afntest::SequenceInputs {});
    if (bright)
        for (int k = 0; k < 3; ++k)
            f.color(kX, kY, k) = kBright;
    auto filter = afnFilter(highlights);
    Image out(kW, kH, 3);
    afntest::runFrame(*filter, f, out);
    if (kept)
        *kept = static_cast<double>(filter->lastHighlightPixels());
    return out;
}

/// The largest change from `base` over the pixels within 3 of the bright one, itself excluded.
double neighbourChange(const Image& a, const Image& base)
{
    double m = 0.0;
    for (int y = kY - 3; y <= kY + 3; ++y)
        for (int x = kX - 3; x <= kX + 3; ++x)
            for (int k = 0; k < 3 && !(x == kX && y == kY); ++k)
                m = std::max(m, static_cast<double>(std::fabs(a(x, y, k) - base(x, y, k))));
    return m;
}

} // namespace

TEST(AfnHighlights, ABrightPixelStaysAPoint)
{
    double kept = -1.0;
    const Image base = run(8.0, false);
    const Image on = run(8.0, true, &kept), off = run(0.0, true);
    EXPECT_EQ(kept, 1.0);
    // Without the bypass the network spreads the pixel over its neighbours (a blotch); with it
    // they barely change.
    const double spreadOff = neighbourChange(off, base), spreadOn = neighbourChange(on, base);
    std::cout << "neighbour change: bypass " << spreadOn << ", off " << spreadOff << "\n";
    EXPECT_GT(spreadOff, 1.0);
    EXPECT_LT(spreadOn, 0.05 * spreadOff);
    // The pixel keeps (almost all of) its energy.
    for (int k = 0; k < 3; ++k)
        EXPECT_GT(on(kX, kY, k), 0.95f * kBright) << k;
}

TEST(AfnHighlights, NothingBrightIsFilteredAsWithTheBypassOff)
{
    double kept = -1.0;
    const Image on = run(8.0, false, &kept), off = run(0.0, false);
    EXPECT_EQ(kept, 0.0);
    EXPECT_TRUE(std::equal(on.data(), on.data() + on.size(), off.data()));
}
