// SPDX-License-Identifier: Apache-2.0
// makeTile codes per role, the bitmap font, fitTile and the contact-sheet layout.
#include "afn/color.hpp"
#include "bitmap_font.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using afn::color::ColorError;
using afn::color::ColorManager;
using afn::color::makeTile;
using afn::color::Tile;

namespace {

void expectPixel(const Tile& t, int x, int y, float r, float g, float b, float tol = 1e-6f)
{
    const float* p = &t.rgb[(static_cast<size_t>(y) * t.width + x) * 3];
    EXPECT_NEAR(p[0], r, tol) << t.label << " at " << x << "," << y;
    EXPECT_NEAR(p[1], g, tol) << t.label << " at " << x << "," << y;
    EXPECT_NEAR(p[2], b, tol) << t.label << " at " << x << "," << y;
}

Tile solid(const std::string& label, int w, int h, float v)
{
    Tile t;
    t.label = label, t.width = w, t.height = h;
    t.rgb.assign(static_cast<size_t>(w) * h * 3, v);
    return t;
}

} // namespace

TEST(ColorTiles, NormalsAreHalfOffset)
{
    ColorManager cm;
    const float n[4 * 3] = { 0, 0, 1, 0, 0, 1, -1, 0, 0, 0, 1, 0 };
    const Tile t = makeTile(cm, "normal", "N", 2, 2, 3, n);
    ASSERT_EQ(t.rgb.size(), 12u);
    expectPixel(t, 0, 0, 0.5f, 0.5f, 1.0f); // +Z
    expectPixel(t, 1, 0, 0.5f, 0.5f, 1.0f);
    expectPixel(t, 0, 1, 0.0f, 0.5f, 0.5f); // -X
    expectPixel(t, 1, 1, 0.5f, 1.0f, 0.5f); // +Y
}

TEST(ColorTiles, DepthIgnoresBlenderBackground)
{
    ColorManager cm;
    // Range [1, 3] from the finite values; 1e10 (no hit) and NaN are black.
    const float d[6] = { 1.f, 2.f, 3.f, 1e10f, std::nanf(""), 1.5f };
    const Tile t = makeTile(cm, "depth", "Z", 3, 2, 1, d);
    expectPixel(t, 0, 0, 1.f, 1.f, 1.f);
    expectPixel(t, 1, 0, 0.5f, 0.5f, 0.5f);
    expectPixel(t, 2, 0, 0.f, 0.f, 0.f);
    expectPixel(t, 0, 1, 0.f, 0.f, 0.f);
    expectPixel(t, 1, 1, 0.f, 0.f, 0.f);
    expectPixel(t, 2, 1, 0.75f, 0.75f, 0.75f);
}

TEST(ColorTiles, PositionNormalisedPerAxis)
{
    ColorManager cm;
    const float p[3 * 3] = { -2, 10, 0, 2, 20, 5, 0, 1e10f, 1e10f };
    const Tile t = makeTile(cm, "position", "P", 3, 1, 3, p);
    expectPixel(t, 0, 0, 0.f, 0.f, 0.f);
    expectPixel(t, 1, 0, 1.f, 1.f, 1.f);
    expectPixel(t, 2, 0, 0.5f, 0.f, 0.f);
}

TEST(ColorTiles, MotionHueIsDirectionValueIsMagnitude)
{
    ColorManager cm;
    // 4 components as Blender's Vector pass; only the first two are used.
    const float m[5 * 4] = { 2, 0, 9, 9, 0, 2, 9, 9, -2, 0, 9, 9, 1, 0, 9, 9, 0, 0, 9, 9 };
    const Tile t = makeTile(cm, "motion", "V", 5, 1, 4, m);
    expectPixel(t, 0, 0, 1.f, 0.f, 0.f); // +x: hue 0 = red, full magnitude
    expectPixel(t, 1, 0, 0.5f, 1.f, 0.f); // +y: hue 90 deg = (0.5, 1, 0) in HSV
    expectPixel(t, 2, 0, 0.f, 1.f, 1.f); // -x: hue 180 deg = cyan
    expectPixel(t, 3, 0, 0.5f, 0.f, 0.f); // half magnitude
    expectPixel(t, 4, 0, 0.f, 0.f, 0.f); // no motion
}

TEST(ColorTiles, ColourGoesThroughTheView)
{
    ColorManager cm;
    const float c[2 * 3] = { 0.18f, 0.18f, 0.18f, std::nanf(""), 100.f, -1.f };
    const float srgb018 = float(1.055 * std::pow(0.18, 1 / 2.4) - 0.055); // 0.46135
    const Tile t = makeTile(cm, "color", "beauty", 2, 1, 3, c);
    expectPixel(t, 0, 0, srgb018, srgb018, srgb018, 2e-4f);
    expectPixel(t, 1, 0, 0.f, 1.f, 0.f, 1e-5f); // NaN -> 0, clamped to [0, 1]
    const Tile log = makeTile(cm, "albedo", "log", 1, 1, 3, c, "sRGB", "Log");
    expectPixel(log, 0, 0, 0.4f, 0.4f, 0.4f, 2e-4f); // (log2(0.18) + 12.4739) / 25
    const float grey[1] = { 0.18f };
    const Tile one = makeTile(cm, "color", "grey", 1, 1, 1, grey);
    expectPixel(one, 0, 0, srgb018, srgb018, srgb018, 2e-4f);
}

TEST(ColorTiles, BadInputsThrow)
{
    ColorManager cm;
    const float v[3] = { 0, 0, 1 };
    EXPECT_THROW(makeTile(cm, "normal", "N", 1, 1, 1, v), ColorError);
    EXPECT_THROW(makeTile(cm, "motion", "V", 1, 1, 1, v), ColorError);
    EXPECT_THROW(makeTile(cm, "color", "C", 0, 1, 3, v), ColorError);
    EXPECT_THROW(makeTile(cm, "color", "C", 1, 1, 3, nullptr), ColorError);
    EXPECT_THROW(makeTile(cm, "color", "C", 1, 1, 3, v, "sRGB", "NoView"), ColorError);
}

TEST(ColorTiles, FontGlyphPixelCounts)
{
    namespace font = afn::color::font;
    // From the glyph art: 'A' has 18 lit font pixels, 'H' 17, ' ' none; each is 2x2 at scale 2.
    std::vector<float> img(40 * 20 * 3, 0.f);
    const float ink[3] = { 1, 1, 1 };
    EXPECT_EQ(font::drawText(img.data(), 40, 20, 0, 0, "A", 2, ink), 72);
    EXPECT_EQ(font::drawText(img.data(), 40, 20, 0, 0, "H", 1, ink), 17);
    EXPECT_EQ(font::drawText(img.data(), 40, 20, 0, 0, " ", 2, ink), 0);
    EXPECT_EQ(font::textWidth("AB", 2), (2 * 6 - 1) * 2);
    EXPECT_EQ(font::glyph('\x01'), font::glyph('?'));
    // Clipped at the image edge: only the left 3 columns of 'H' at x = 37..39: column 0 in 7
    // rows plus columns 1 and 2 of the bar row = 9.
    std::vector<float> small(40 * 20 * 3, 0.f);
    EXPECT_EQ(font::drawText(small.data(), 40, 20, 37, 0, "H", 1, ink), 9);
}

TEST(ColorTiles, FontHasDescendersAndFitsLines)
{
    namespace font = afn::color::font;
    // 'g' is not '9': it reaches below the baseline, '9' does not.
    auto below = [](char c) {
        const std::uint8_t* rows = font::glyph(c);
        return rows[font::kAscent] | rows[font::kAscent + 1];
    };
    for (char c : std::string("gjpqy"))
        EXPECT_NE(below(c), 0) << c;
    for (char c : std::string("9aAZ0"))
        EXPECT_EQ(below(c), 0) << c;
    // Lines of whole glyphs within the width, broken after separators, ellipsised when too long.
    const int w = font::textWidth("0123456789", 2); // 10 characters per line
    auto lines = font::fitLines("albedo: ViewLayer.Denoising Albedo", 2, w, 2);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], "albedo:");
    EXPECT_EQ(lines[1], "ViewLay...");
    for (const std::string& l : lines)
        EXPECT_LE(font::textWidth(l, 2), w) << l;
    EXPECT_EQ(font::fitLines("short", 2, w, 2), std::vector<std::string> { "short" });
    EXPECT_EQ(font::fitLines("abcdefghijklmno", 2, w, 2),
        (std::vector<std::string> { "abcdefghij", "klmno" }));
    EXPECT_TRUE(font::fitLines("", 2, w, 2).empty());
}

TEST(ColorTiles, ContactSheetLayoutAndLabels)
{
    using namespace afn::color;
    std::vector<Tile> tiles { solid("A", 10, 8, 1.f), solid("", 6, 4, 0.5f),
        solid("A", 10, 8, 0.f) };
    int w = 0, h = 0;
    const std::vector<float> sheet = layoutContactSheet(tiles, 2, w, h);
    // 2 columns, 2 rows of cells kSheetMinCellWidth wide (the tiles are narrower) and 8 high.
    const int cellW = kSheetMinCellWidth, rowH = kSheetLabelBand + 8 + kSheetGap;
    ASSERT_EQ(w, kSheetGap + 2 * (cellW + kSheetGap));
    ASSERT_EQ(h, kSheetGap + 2 * rowH);
    ASSERT_EQ(sheet.size(), size_t(w) * h * 3);
    auto at = [&](int x, int y) { return sheet[(static_cast<size_t>(y) * w + x) * 3]; };
    const int col1 = kSheetGap + cellW + kSheetGap, tileY = kSheetGap + kSheetLabelBand;
    EXPECT_EQ(at(kSheetGap, tileY), 1.f);
    EXPECT_EQ(at(kSheetGap + 9, tileY + 7), 1.f);
    EXPECT_EQ(at(kSheetGap + 10, tileY), kSheetBackground); // right of the tile, in its cell
    EXPECT_EQ(at(col1, tileY), 0.5f);
    EXPECT_EQ(at(col1 + 5, tileY + 3), 0.5f);
    EXPECT_EQ(at(col1 + 6, tileY), kSheetBackground);
    EXPECT_EQ(at(kSheetGap, tileY + rowH), 0.f);
    // Label bands: "A" lights exactly 72 pixels (18 glyph pixels at 2x2), the empty label none.
    auto inked = [&](int x0, int y0) {
        int count = 0;
        for (int y = y0; y < y0 + kSheetLabelBand; ++y)
            for (int x = x0; x < x0 + cellW; ++x)
                count += at(x, y) != kSheetBackground;
        return count;
    };
    EXPECT_EQ(inked(kSheetGap, kSheetGap), 72);
    EXPECT_EQ(inked(col1, kSheetGap), 0);
    EXPECT_EQ(inked(kSheetGap, kSheetGap + rowH), 72);
    // Automatic columns: ceil(sqrt(5)) = 3.
    std::vector<Tile> five(5, solid("x", 4, 4, 0.f));
    layoutContactSheet(five, 0, w, h);
    EXPECT_EQ(w, kSheetGap + 3 * (cellW + kSheetGap));
    EXPECT_EQ(h, kSheetGap + 2 * (kSheetLabelBand + 4 + kSheetGap));
    EXPECT_THROW(layoutContactSheet({}, 2, w, h), ColorError);
    Tile broken = solid("b", 4, 4, 0.f);
    broken.rgb.pop_back();
    EXPECT_THROW(layoutContactSheet({ broken }, 1, w, h), ColorError);
}

TEST(ColorTiles, FitTileBoxFilters)
{
    using afn::color::fitTile;
    Tile t = solid("big", 8, 4, 0.f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int k = 0; k < 3; ++k)
                t.rgb[(y * 8 + x) * 3 + k] = float(x + 8 * y);
    const Tile f = fitTile(t, 4, 4); // scale 0.5 -> 4x2, each pixel the mean of a 2x2 block
    ASSERT_EQ(f.width, 4);
    ASSERT_EQ(f.height, 2);
    expectPixel(f, 0, 0, 4.5f, 4.5f, 4.5f); // (0 + 1 + 8 + 9) / 4
    expectPixel(f, 3, 1, 26.5f, 26.5f, 26.5f); // (22 + 23 + 30 + 31) / 4
    EXPECT_EQ(fitTile(t, 100, 100).width, 8);
    EXPECT_EQ(f.label, "big");
}
