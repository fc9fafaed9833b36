// SPDX-License-Identifier: Apache-2.0
// layoutContactSheet and fitTile: labelled tiles on a grid (labels fitted to their cell), and
// box-filtered tile downscaling.
#include "afn/color.hpp"
#include "bitmap_font.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace afn::color {

static_assert(kSheetLineHeight == (font::kGlyphHeight + 1) * kSheetLabelScale,
    "kSheetLineHeight must follow the font height");
static_assert(kSheetLabelBand >= kSheetLabelLines * kSheetLineHeight,
    "the label band must hold kSheetLabelLines lines");
static_assert(kSheetMinCellWidth >= 16 * font::kAdvance * kSheetLabelScale - kSheetLabelScale,
    "the narrowest cell must hold 16 characters");

Tile fitTile(const Tile& tile, int maxWidth, int maxHeight)
{
    if (tile.width <= 0 || tile.height <= 0
        || tile.rgb.size() != static_cast<size_t>(tile.width) * tile.height * 3)
        throw ColorError(
            "fitTile: tile size does not match its pixels (tile '" + tile.label + "')");
    if (maxWidth <= 0 || maxHeight <= 0)
        throw ColorError("fitTile: maximum size must be positive (tile '" + tile.label + "')");
    const double scale
        = std::min({ 1.0, double(maxWidth) / tile.width, double(maxHeight) / tile.height });
    if (scale >= 1.0)
        return tile;
    Tile out;
    out.label = tile.label;
    out.width = std::max(1, static_cast<int>(std::floor(tile.width * scale)));
    out.height = std::max(1, static_cast<int>(std::floor(tile.height * scale)));
    out.rgb.assign(static_cast<size_t>(out.width) * out.height * 3, 0.f);
    // Each output pixel averages the source pixels whose index maps into it (box filter).
    for (int y = 0; y < out.height; ++y) {
        const int y0 = y * tile.height / out.height, y1 = (y + 1) * tile.height / out.height;
        for (int x = 0; x < out.width; ++x) {
            const int x0 = x * tile.width / out.width, x1 = (x + 1) * tile.width / out.width;
            float sum[3] = { 0, 0, 0 };
            for (int sy = y0; sy < y1; ++sy)
                for (int sx = x0; sx < x1; ++sx)
                    for (int k = 0; k < 3; ++k)
                        sum[k] += tile.rgb[(static_cast<size_t>(sy) * tile.width + sx) * 3 + k];
            const float count = float((y1 - y0) * (x1 - x0));
            for (int k = 0; k < 3; ++k)
                out.rgb[(static_cast<size_t>(y) * out.width + x) * 3 + k] = sum[k] / count;
        }
    }
    return out;
}

std::vector<float> layoutContactSheet(
    const std::vector<Tile>& tiles, int columns, int& outWidth, int& outHeight)
{
    if (tiles.empty())
        throw ColorError("contact sheet: no tiles");
    int cellW = 0, cellH = 0;
    for (const Tile& t : tiles) {
        if (t.width <= 0 || t.height <= 0
            || t.rgb.size() != static_cast<size_t>(t.width) * t.height * 3)
            throw ColorError(
                "contact sheet: tile size does not match its pixels (tile '" + t.label + "')");
        cellW = std::max(cellW, t.width), cellH = std::max(cellH, t.height);
    }
    cellW = std::max(cellW, kSheetMinCellWidth);
    const int n = static_cast<int>(tiles.size());
    if (columns <= 0)
        columns = static_cast<int>(std::ceil(std::sqrt(double(n))));
    columns = std::min(columns, n);
    const int rows = (n + columns - 1) / columns;
    outWidth = kSheetGap + columns * (cellW + kSheetGap);
    outHeight = kSheetGap + rows * (kSheetLabelBand + cellH + kSheetGap);

    std::vector<float> sheet(static_cast<size_t>(outWidth) * outHeight * 3, kSheetBackground);
    const float ink[3] = { 0.92f, 0.92f, 0.92f };
    for (int i = 0; i < n; ++i) {
        const Tile& t = tiles[i];
        const int x0 = kSheetGap + (i % columns) * (cellW + kSheetGap);
        const int y0 = kSheetGap + (i / columns) * (kSheetLabelBand + cellH + kSheetGap);
        const std::vector<std::string> lines
            = font::fitLines(t.label, kSheetLabelScale, cellW, kSheetLabelLines);
        // The lines centred vertically in the band (no gap row under the last one).
        const int textHeight = static_cast<int>(lines.size()) * kSheetLineHeight
            - (kSheetLineHeight - font::kGlyphHeight * kSheetLabelScale);
        int textY = y0 + (kSheetLabelBand - textHeight) / 2;
        for (const std::string& line : lines) {
            font::drawText(
                sheet.data(), outWidth, outHeight, x0, textY, line, kSheetLabelScale, ink, cellW);
            textY += kSheetLineHeight;
        }
        // Tiles smaller than the cell sit at its top-left, under their label.
        for (int y = 0; y < t.height; ++y) {
            const float* src = t.rgb.data() + static_cast<size_t>(y) * t.width * 3;
            float* dst = sheet.data()
                + (static_cast<size_t>(y0 + kSheetLabelBand + y) * outWidth + x0) * 3;
            std::copy(src, src + static_cast<size_t>(t.width) * 3, dst);
        }
    }
    return sheet;
}

} // namespace afn::color
