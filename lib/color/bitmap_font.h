// SPDX-License-Identifier: Apache-2.0
// A built-in bitmap font for printable ASCII (5 columns, 7 rows above the baseline and 2 below for
// the descenders of g, j, p, q, y), used to label contact-sheet tiles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace afn::color::font {

constexpr int kGlyphWidth = 5; ///< glyph cell width in font pixels
constexpr int kAscent = 7; ///< font pixels above the baseline (capitals, digits)
constexpr int kGlyphHeight = 9; ///< glyph cell height in font pixels: ascent + 2 descender rows
constexpr int kAdvance = 6; ///< horizontal advance per character (one column of spacing)

/// The kGlyphHeight rows of a glyph, top to bottom; bit 4 of each row is the leftmost pixel.
/// Characters outside printable ASCII (32..126) map to '?'.
const std::uint8_t* glyph(char c);

/// Width in image pixels of `text` drawn at integer `scale` (no trailing spacing column).
int textWidth(const std::string& text, int scale);

/// Split `text` into at most `maxLines` lines of whole glyphs, each at most `maxWidth` image
/// pixels wide at `scale`. Lines break after '.', ' ', ':', '/', '_' or '-' where possible (else
/// inside a word); text that still does not fit ends in "..." on the last line. Empty text gives
/// no lines; a width below one "..." gives as many characters as fit (possibly none).
std::vector<std::string> fitLines(const std::string& text, int scale, int maxWidth, int maxLines);

/// Draw `text` into an RGB float image (width x height, 3 floats per pixel) with its top-left
/// corner at (x, y), each font pixel a scale x scale block; clipped to the image and, when
/// `maxWidth` > 0, to x + maxWidth. Returns the number of image pixels set.
int drawText(float* rgb, int width, int height, int x, int y, const std::string& text, int scale,
    const float color[3], int maxWidth = 0);

} // namespace afn::color::font
