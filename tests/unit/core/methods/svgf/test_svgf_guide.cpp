// SPDX-License-Identifier: Apache-2.0
// SVGF's depth gradient guide (methods/svgf/guide.h): per axis the one-sided difference of smaller
// magnitude, the backward one as -(previous - z) (so -0 where the neighbour is equal), one side at
// the border, 0 for a one-pixel axis; compared bit for bit with the rule written out here, on
// random depths with ties and equal neighbours, and on 1-pixel-wide and 1-pixel-high frames.
#include "methods/svgf/guide.h"
#include "methods/svgf/settings.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace {

using afn::Frame;
using afn::Image;

/// The rule as the scalar code before the vectorised row stated it: visit the backward then the
/// forward neighbour, keep the first, replace it by a later one of smaller magnitude.
float literalAxis(const Image& z, int x, int y, int dx, int dy)
{
    float best = 0.0f;
    bool any = false;
    for (int sgn = -1; sgn <= 1; sgn += 2) {
        const int nx = x + sgn * dx, ny = y + sgn * dy;
        if (nx < 0 || ny < 0 || nx >= z.width() || ny >= z.height())
            continue;
        const float d = static_cast<float>(sgn) * (z(nx, ny, 0) - z(x, y, 0));
        if (!any || std::fabs(d) < std::fabs(best))
            best = d;
        any = true;
    }
    return best;
}

void expectGradientOf(int w, int h, std::uint32_t seed)
{
    methods_test::Lcg rng { seed };
    Frame f;
    f.width = w;
    f.height = h;
    // Depths on a coarse grid of values, so that equal neighbours and equal magnitudes occur.
    f.depth = methods_test::makeImage(
        w, h, 1, [&](int, int, int) { return 2.0f + 0.25f * std::floor(4.0f * rng.next()); });
    afn::svgf::Guide g;
    g.build(f, afn::svgf::Settings {});
    ASSERT_TRUE(g.hasDepth);
    int negativeZeros = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float gx = g.planes.row(afn::svgf::kDepthDx, y)[x];
            const float gy = g.planes.row(afn::svgf::kDepthDy, y)[x];
            const float ex = literalAxis(f.depth, x, y, 1, 0);
            const float ey = literalAxis(f.depth, x, y, 0, 1);
            ASSERT_EQ(std::memcmp(&gx, &ex, sizeof gx), 0)
                << w << "x" << h << " at " << x << "," << y << ": " << gx << " vs " << ex;
            ASSERT_EQ(std::memcmp(&gy, &ey, sizeof gy), 0)
                << w << "x" << h << " at " << x << "," << y << ": " << gy << " vs " << ey;
            negativeZeros += std::signbit(ex) && ex == 0.0f;
        }
    if (w > 2 && h > 2)
        EXPECT_GT(negativeZeros, 0) << "no equal neighbours: the -0 case is not exercised";
}

TEST(SvgfGuide, DepthGradientIsTheSmallerOneSidedDifference)
{
    expectGradientOf(53, 7, 1u); // three 16-lane blocks and a tail
    expectGradientOf(1, 9, 2u);
    expectGradientOf(17, 1, 3u);
    expectGradientOf(1, 1, 4u);
    expectGradientOf(2, 2, 5u);
}

} // namespace
