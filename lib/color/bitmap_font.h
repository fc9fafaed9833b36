// SPDX-License-Identifier: Apache-2.0
// A built-in 5x7 bitmap font for printable ASCII, used to label contact-sheet tiles.
#pragma once

#include <cstdint>
#include <string>

namespace afn::color::font {

constexpr int kGlyphWidth = 5; ///< glyph cell width in font pixels
constexpr int kGlyphHeight = 7; ///< glyph cell height in font pixels
constexpr int kAdvance = 6; ///< horizontal advance per character (one column of spacing)

/// The 7 rows of a glyph, top to bottom; bit 4 of each row is the leftmost pixel. Characters
/// outside printable ASCII (32..126) map to '?'.
const std::uint8_t* glyph(char c);

/// Width in image pixels of `text` drawn at integer `scale` (no trailing spacing column).
int textWidth(const std::string& text, int scale);

/// Draw `text` into an RGB float image (width x height, 3 floats per pixel) with its top-left
/// corner at (x, y), each font pixel a scale x scale block; clipped to the image and, when
/// `maxWidth` > 0, to x + maxWidth. Returns the number of image pixels set.
int drawText(float* rgb, int width, int height, int x, int y, const std::string& text, int scale,
    const float color[3], int maxWidth = 0);

} // namespace afn::color::font
