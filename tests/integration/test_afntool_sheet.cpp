// SPDX-License-Identifier: Apache-2.0
// afntool --contact-sheet end to end, measured on the written pixels: every layer shown once,
// labels inside their cells in whole glyphs, layers outside the roles shown as grey, vector or
// normalised tiles (not raw red/green).
#include "cli_runner.h"

#include "afn/color.hpp"
#include "afn/io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace {

using afn::color::kSheetGap;
using afn::color::kSheetLabelBand;

const std::string kBlender = std::string(AFN_TEST_DATA) + "/blender_64x36.exr";

struct Sheet {
    int width = 0, height = 0;
    std::vector<float> rgb;
    const float* at(int x, int y) const { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
    /// Differs from the background (sampled in the top-left gap, whatever the PNG decoding).
    bool ink(int x, int y) const
    {
        const float* p = at(x, y);
        const float* b = at(0, 0);
        return std::fabs(p[0] - b[0]) + std::fabs(p[1] - b[1]) + std::fabs(p[2] - b[2]) > 1e-3f;
    }
};

Sheet readSheet(const std::string& path)
{
    const afn::io::FrameImages img = afn::io::readFrame(path);
    const afn::io::RoleImage& c = img.roles.at(afn::io::Role::Color);
    Sheet s;
    s.width = c.width, s.height = c.height;
    s.rgb.resize(static_cast<size_t>(c.width) * c.height * 3);
    for (size_t i = 0; i < static_cast<size_t>(c.width) * c.height; ++i)
        for (int k = 0; k < 3; ++k)
            s.rgb[i * 3 + k] = c.pixels[i * c.components + std::min(k, c.components - 1)];
    return s;
}

/// Writes a float EXR of `channels` (interleaved `px`) into `dir`, runs
/// `afntool in.exr --contact-sheet:columns=N c.png` and reads the sheet back.
Sheet sheetOfChannels(const TempDir& dir, int w, int h, const std::vector<std::string>& channels,
    const std::vector<float>& px, int columns)
{
    afn::io::WriteOptions wo;
    wo.dataType = "float";
    afn::io::writeImageAtomic(dir.file("in.exr"), w, h, channels, px.data(), wo);
    const CliResult r = runAfntool({ dir.file("in.exr"),
        "--contact-sheet:columns=" + std::to_string(columns), dir.file("c.png") });
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return r.exitCode == 0 ? readSheet(dir.file("c.png")) : Sheet {};
}

/// Layout of a sheet of tiles of tileW x tileH in `columns` columns (include/afn/color.hpp).
struct Grid {
    int columns, cellW, cellH, rows;
    Grid(const Sheet& s, int cols, int tileH)
        : columns(cols)
        , cellW((s.width - kSheetGap) / cols - kSheetGap)
        , cellH(tileH)
        , rows((s.height - kSheetGap) / (kSheetLabelBand + tileH + kSheetGap))
    {
    }
    int x0(int i) const { return kSheetGap + (i % columns) * (cellW + kSheetGap); }
    int y0(int i) const
    {
        return kSheetGap + (i / columns) * (kSheetLabelBand + cellH + kSheetGap);
    }
};

/// Layers of the file: channel names up to their last '.'.
std::set<std::string> layersOf(const std::vector<std::string>& channels)
{
    std::set<std::string> out;
    for (const std::string& c : channels)
        out.insert(c.substr(0, c.rfind('.')));
    return out;
}

} // namespace

TEST(AfntoolSheet, EveryLayerIsShownOnce)
{
    // Expected: the colour tile, one tile per other mapped role, one per layer no role reads from.
    // Blender's Vector layer is read by the motion role (X, Y) and must not come back as an
    // "other layer" for its unused Z, W.
    afn::io::ReadOptions ro;
    ro.keepAll = true;
    const afn::io::FrameImages img = afn::io::readFrame(kBlender, ro);
    std::set<std::string> roleLayers;
    int roles = 0;
    for (const afn::io::RoleChannels& rc : img.mapping.roles)
        if (img.roles.count(rc.role)) {
            ++roles;
            for (const std::string& ch : rc.channels)
                roleLayers.insert(ch.substr(0, ch.rfind('.')));
        }
    int expected = roles;
    for (const std::string& layer : layersOf(img.all->channels))
        expected += !roleLayers.count(layer);

    TempDir dir;
    const CliResult r = runAfntool({ kBlender, "--contact-sheet:columns=1", dir.file("c.png") });
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Sheet s = readSheet(dir.file("c.png"));
    const Grid g(s, 1, img.all->height);
    EXPECT_EQ(g.rows * (kSheetLabelBand + g.cellH + kSheetGap) + kSheetGap, s.height);
    EXPECT_EQ(g.rows, expected) << "tiles on the sheet against roles + unread layers";
}

TEST(AfntoolSheet, LabelsStayInsideTheirCellInWholeGlyphs)
{
    // Long layer names in a narrow frame: every label must be drawn, inside its own cell and
    // label band, never cut at the cell's right edge (a cut glyph leaves ink in the last columns;
    // a whole glyph at scale 2 ends at an even offset before it).
    TempDir dir;
    const int w = 64, h = 36;
    const std::vector<std::string> channels
        = { "R", "G", "B", "LightGroup_KeyLight_with_a_very_long_name.Lumi",
              "Another.Long.Layer.Name.For.Testing.V", "short.Z" };
    std::vector<float> px(static_cast<size_t>(w) * h * channels.size());
    for (size_t i = 0; i < px.size(); ++i)
        px[i] = float((i / channels.size()) % w) / w;
    const Sheet s = sheetOfChannels(dir, w, h, channels, px, 2);
    ASSERT_GT(s.width, 0);
    const Grid g(s, 2, h);
    ASSERT_EQ(g.rows, 2) << "colour + 3 layers in 2 columns";
    for (int i = 0; i < 4; ++i) {
        int inked = 0, right = -1;
        for (int y = g.y0(i); y < g.y0(i) + kSheetLabelBand; ++y)
            for (int x = g.x0(i) - kSheetGap + 1; x < g.x0(i) + g.cellW + kSheetGap - 1; ++x) {
                if (x < 0 || x >= s.width || !s.ink(x, y))
                    continue;
                ++inked;
                right = std::max(right, x - g.x0(i));
                EXPECT_GE(x, g.x0(i)) << "label " << i << " starts left of its cell";
                EXPECT_LT(x, g.x0(i) + g.cellW) << "label " << i << " runs into the next cell";
            }
        EXPECT_GT(inked, 0) << "label " << i << " missing";
        EXPECT_LT(right, g.cellW - 2) << "label " << i << " cut at the cell edge";
    }
    // Nothing of a label is drawn in the gap rows between bands and tiles of the row above.
    for (int x = 0; x < s.width; ++x)
        EXPECT_FALSE(s.ink(x, kSheetGap - 1)) << "ink above the first label band at x=" << x;
}

TEST(AfntoolSheet, LayersOutsideTheRolesAreShownByTheirChannels)
{
    // A 1-channel layer (a ramp 0..10) must be grey and span the display range; a 2-channel
    // vector layer pointing every way must be colour coded (several hues, not red/green only).
    TempDir dir;
    const int w = 96, h = 64;
    const std::vector<std::string> channels = { "R", "G", "B", "custom.V", "flow.U", "flow.V" };
    std::vector<float> px(static_cast<size_t>(w) * h * channels.size(), 0.2f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &px[(static_cast<size_t>(y) * w + x) * channels.size()];
            p[3] = 10.f * x / (w - 1);
            p[4] = float(x - w / 2), p[5] = float(h / 2 - y);
        }
    const Sheet s = sheetOfChannels(dir, w, h, channels, px, 1);
    ASSERT_GT(s.width, 0);
    const Grid g(s, 1, h);
    ASSERT_EQ(g.rows, 3) << "colour, custom, flow";

    float lo = 1.f, hi = 0.f, maxChroma = 0.f;
    const int ty = g.y0(1) + kSheetLabelBand;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = s.at(g.x0(1) + x, ty + y);
            maxChroma = std::max({ maxChroma, std::fabs(p[0] - p[1]), std::fabs(p[1] - p[2]) });
            lo = std::min(lo, p[0]), hi = std::max(hi, p[0]);
        }
    EXPECT_LT(maxChroma, 0.01f) << "a 1-channel layer must be grey";
    EXPECT_LT(lo, 0.05f);
    EXPECT_GT(hi, 0.95f) << "normalised to its range";

    // Vector tile: count pixels where blue dominates and where green dominates (a red-only or
    // red/green tile has no blue-dominant pixels).
    int blue = 0, green = 0, red = 0;
    const int vy = g.y0(2) + kSheetLabelBand;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = s.at(g.x0(2) + x, vy + y);
            blue += p[2] > 0.3f && p[2] > p[0] + 0.1f && p[2] > p[1] + 0.1f;
            green += p[1] > 0.3f && p[1] > p[0] + 0.1f && p[1] > p[2] + 0.1f;
            red += p[0] > 0.3f && p[0] > p[1] + 0.1f && p[0] > p[2] + 0.1f;
        }
    EXPECT_GT(blue, w * h / 20);
    EXPECT_GT(green, w * h / 20);
    EXPECT_GT(red, w * h / 20);
}
