// SPDX-License-Identifier: Apache-2.0
// makeTile: display-referred pictures of AOVs (colour through OCIO, data roles by analytic codes).
#include "afn/color.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace afn::color {
namespace {

// Blender writes 1e10 for depth/position where a ray hits nothing; values at or beyond this
// magnitude are treated as "no surface" and kept out of the normalisation range.
constexpr float kBackground = 1e9f;

bool valid(float v)
{
    return std::isfinite(v) && std::fabs(v) < kBackground;
}

float clamp01(float v)
{
    return std::isfinite(v) ? std::min(1.f, std::max(0.f, v)) : 0.f;
}

bool isColorLike(const std::string& kind)
{
    static const char* const kinds[] = { "color", "albedo", "reference", "beauty", "diffuse",
        "specular", "emission", "rgb", "denoised", "output" };
    for (const char* k : kinds)
        if (kind == k)
            return true;
    return false;
}

// HSV with s = 1 to RGB; h in [0, 1).
void hueValue(float h, float v, float* rgb)
{
    const float h6 = h * 6.f;
    const int sector = static_cast<int>(std::floor(h6)) % 6;
    const float f = h6 - std::floor(h6);
    const float up = v * f, down = v * (1.f - f);
    const float table[6][3] = { { v, up, 0 }, { down, v, 0 }, { 0, v, up }, { 0, down, v },
        { up, 0, v }, { v, 0, down } };
    std::copy(table[sector], table[sector] + 3, rgb);
}

// Min and max of channel c over pixels whose `c` value is valid; false when none is.
bool finiteRange(const float* px, size_t n, int comps, int c, float& lo, float& hi)
{
    lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (size_t i = 0; i < n; ++i) {
        const float v = px[i * comps + c];
        if (valid(v))
            lo = std::min(lo, v), hi = std::max(hi, v);
    }
    return lo <= hi;
}

float normalise(float v, float lo, float hi)
{
    if (!valid(v))
        return 0.f;
    return hi > lo ? (v - lo) / (hi - lo) : 0.5f;
}

std::string shortNumber(float v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", double(v));
    return buf;
}

/// Direction legend of the vector code in the bottom-right corner of a tile: a disc whose pixel
/// at offset (dx, dy) from the centre shows the code of a vector pointing that way (+y drawn up),
/// its magnitude growing to the maximum at the rim; a grey ring separates it from the picture.
/// Drawn only on tiles of at least kLegendMinSide pixels on both sides.
void drawDirectionLegend(float* rgb, int width, int height)
{
    constexpr int kLegendMinSide = 48;
    if (std::min(width, height) < kLegendMinSide)
        return;
    const int radius = std::clamp(std::min(width, height) / 8, 8, 28);
    const int cx = width - radius - 4, cy = height - radius - 4;
    constexpr float kTwoPi = 6.2831853f;
    for (int y = cy - radius - 2; y <= cy + radius + 2; ++y)
        for (int x = cx - radius - 2; x <= cx + radius + 2; ++x) {
            const float dx = float(x - cx), dy = float(cy - y);
            const float r = std::hypot(dx, dy);
            float* p = rgb + (static_cast<size_t>(y) * width + x) * 3;
            if (r <= radius) {
                float h = std::atan2(dy, dx) / kTwoPi;
                h = h < 0.f ? h + 1.f : h;
                hueValue(std::min(h, 0.99999f), r / radius, p);
            } else if (r <= radius + 2.f) {
                p[0] = p[1] = p[2] = 0.6f;
            }
        }
}

} // namespace

Tile makeTile(const ColorManager& cm, const std::string& kind, const std::string& label, int width,
    int height, int components, const float* pixels, const std::string& display,
    const std::string& view)
{
    const std::string what = " (tile '" + label + "', kind '" + kind + "')";
    if (width <= 0 || height <= 0 || components <= 0 || !pixels)
        throw ColorError("makeTile: empty image or null pixels" + what);
    Tile tile;
    tile.label = label, tile.width = width, tile.height = height;
    const size_t n = static_cast<size_t>(width) * height;
    tile.rgb.assign(n * 3, 0.f);
    float* out = tile.rgb.data();
    const int c = components;
    auto channel = [&](size_t i, int k) { return pixels[i * c + std::min(k, c - 1)]; };

    if (isColorLike(kind)) {
        // One channel is shown as grey; NaN/Inf become 0 before OCIO (they would propagate).
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) {
                const float v = channel(i, k);
                out[i * 3 + k] = std::isfinite(v) ? v : 0.f;
            }
        cm.toDisplay(out, width, height, 3, {}, display, view);
        for (float& v : tile.rgb)
            v = clamp01(v);
    } else if (kind == "normal") {
        if (c < 3)
            throw ColorError("makeTile: a normal needs 3 components" + what);
        for (size_t i = 0; i < n * 3; ++i)
            out[i] = clamp01(channel(i / 3, static_cast<int>(i % 3)) * 0.5f + 0.5f);
    } else if (kind == "depth") {
        // Near = bright, far = dark; background (no surface) = black.
        float lo, hi;
        finiteRange(pixels, n, c, 0, lo, hi);
        for (size_t i = 0; i < n; ++i) {
            const float v = pixels[i * c];
            const float g = valid(v) ? 1.f - normalise(v, lo, hi) : 0.f;
            out[i * 3] = out[i * 3 + 1] = out[i * 3 + 2] = g;
        }
    } else if (kind == "position") {
        // Each axis normalised by its own finite range: x -> red, y -> green, z -> blue.
        for (int k = 0; k < std::min(c, 3); ++k) {
            float lo, hi;
            finiteRange(pixels, n, c, k, lo, hi);
            for (size_t i = 0; i < n; ++i)
                out[i * 3 + k] = normalise(pixels[i * c + k], lo, hi);
        }
    } else if (kind == "motion" || kind == "vector2") {
        // Motion and any 2D vector (kind "vector2"): hue = direction of (x, y) (0 deg = +x = red,
        // counter-clockwise), value = magnitude over the largest finite magnitude in the image; no
        // motion is black. Blender's 4-channel Vector pass: the first two channels (motion towards
        // the previous frame) are used.
        if (c < 2)
            throw ColorError("makeTile: motion needs 2 components" + what);
        float maxMag = 0.f;
        for (size_t i = 0; i < n; ++i) {
            const float x = pixels[i * c], y = pixels[i * c + 1];
            if (valid(x) && valid(y))
                maxMag = std::max(maxMag, std::hypot(x, y));
        }
        constexpr float kTwoPi = 6.2831853f;
        for (size_t i = 0; i < n; ++i) {
            const float x = pixels[i * c], y = pixels[i * c + 1];
            if (!(valid(x) && valid(y)) || maxMag <= 0.f)
                continue;
            float h = std::atan2(y, x) / kTwoPi;
            h = h < 0.f ? h + 1.f : h;
            hueValue(std::min(h, 0.99999f), std::hypot(x, y) / maxMag, out + i * 3);
        }
        drawDirectionLegend(out, width, height);
        tile.label += " (max length " + shortNumber(maxMag) + ")";
    } else if (kind == "alpha" || kind == "mask") {
        for (size_t i = 0; i < n * 3; ++i)
            out[i] = clamp01(pixels[(i / 3) * c]);
    } else {
        // Anything else (variance, unknown AOVs, kind "data"): every shown channel normalised by
        // the joint finite range of the first min(c, 3) channels (one channel: grey); the range
        // is appended to the label.
        float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
        for (int k = 0; k < std::min(c, 3); ++k) {
            float l, h;
            if (finiteRange(pixels, n, c, k, l, h))
                lo = std::min(lo, l), hi = std::max(hi, h);
        }
        for (size_t i = 0; i < n * 3; ++i)
            out[i] = normalise(channel(i / 3, static_cast<int>(i % 3)), lo, hi);
        if (lo <= hi)
            tile.label += " [" + shortNumber(lo) + ", " + shortNumber(hi) + "]";
    }
    return tile;
}

} // namespace afn::color
