// SPDX-License-Identifier: Apache-2.0
// Highlights that bypass a spatial filter: emitters and other pixels far brighter than the frame.
//
// The problem. A light source smaller than a pixel (a lamp, a glint of the sun, a bright LED) is
// hit by a few of a pixel's 1-spp samples over time. Each hit is a value hundreds or thousands of
// times the frame's level (a held-out render: 5716 where the surrounding wall is 0.1, the
// reference pixel 134-335); the temporal accumulation keeps it at its pixel for about ten
// frames, which is right (its mean over time is the pixel's true value). A spatial filter is not
// made for such values: a 7x7 kernel that gives the pixel's neighbours a weight of 1 % spreads
// 1 % of 5716 over them, and afn's and svgf's outputs showed a bright blotch of 8x8 pixels at
// 20-100 for the ten frames the history holds the hit, where the reference is a 2x2 lamp on a dark
// wall; bmfr's regression bent its whole 32x32 block (docs/afn-evaluation.md, "Highlights").
// (The renderer's albedo does not help: Cycles writes the emission into Denoising Albedo, which
// the input gather clamps to 1 as no reflectance exceeds it.)
//
// The rule. The filter reads its colour inputs clamped, per channel, at a frame-level limit
//   L = kHighlightFactor * 2^e,  2^e the power of two just above the 99th percentile of the
//                                 largest channel of the accumulated (or only) colour,
//                                 over every 4th row and column
// and the excess of the accumulated colour, max(c - L, 0) per channel, is added back at its own
// pixel after the filter (afn: after its post-filter where that runs, else before its output TAA,
// whose output is its next history; svgf: to its output and its history; bmfr: to its fit,
// before its second accumulation). So every value at or below L, the whole image of almost every
// frame, is filtered as before, bit for bit, and a highlight keeps its energy at its pixel instead
// of becoming a blotch: the temporal accumulation's value there, which is the best per-pixel
// estimate there is. The percentile is a power of two so the limit does not flicker with the noise
// of the frame's statistics. The factor 8 (8-16 times the percentile) is the smallest of 4, 8, 16,
// 64 with which no held-out sequence lost PSNR at 1 or 16 spp (docs/afn-evaluation.md,
// "Highlights"): 4 gained more on average but cost night-1000002 0.05 dB at 1 spp.
// The choice of the accumulated colour for both the limit and the excess: the 1-spp frame's
// bright samples are noise around it; at a disocclusion the accumulation is the frame itself.
#pragma once

#include "base/image.h"
#include "base/parallel.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace afn {

/// Default factor of the limit over the frame's bright level (the "highlights" parameter).
constexpr float kHighlightFactor = 8.0f;

/// Samples of the limit's percentile: every kHighlightStride-th row and column.
constexpr int kHighlightStride = 4;

/// The limit of the file comment from `largest(x, y)`, the largest channel of the accumulated
/// (or only) colour at (x, y), over a w x h frame: `factor` times the power of two just above
/// the 99th percentile over every kHighlightStride-th row and column; +infinity when factor <= 0
/// (bypass off) or the frame is empty. A largest channel of 0 counts as below every power of
/// two; the limit is at least factor * 2^-64.
float highlightLimit(int w, int h, float factor, const std::function<float(int, int)>& largest);
/// highlightLimit() of an interleaved 3-channel image.
float highlightLimit(const Image& accumulated, float factor);

/// The split of the file comment for one frame.
class HighlightBypass {
public:
    /// Find the pixels of a w x h frame whose colour (value(x, y, channel)) exceeds `limit` in
    /// some channel and keep their excess, max(value - limit, 0) per channel; none when the limit
    /// is +infinity.
    template <typename Value> void split(int w, int h, float limit, Value&& value)
    {
        if (!begin(limit, h))
            return;
        // Rows in parallel, each row's pixels in order, then the rows in order.
        parallelRows(h, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < w; ++x) {
                    const float v[3] = { value(x, y, 0), value(x, y, 1), value(x, y, 2) };
                    if (v[0] > limit || v[1] > limit || v[2] > limit)
                        keep(x, y, v);
                }
        });
        finish();
    }
    /// split() of an interleaved 3-channel image (clamped() of that image then needs no scan).
    void split(const Image& accumulated, float limit);
    /// `img` (3 ch) clamped at the split's limit: `img` itself when none of its values exceeds
    /// it, else a copy clamped per channel held in slot `slot` (0 or 1; valid until the next
    /// clamped() with that slot).
    const Image& clamped(const Image& img, int slot);
    /// Call fn(x, y, excess) for each kept pixel, in row order (excess: 3 floats).
    template <typename Fn> void forEach(Fn&& fn) const
    {
        for (const Excess& e : m_excess)
            fn(e.x, e.y, e.value);
    }
    /// Add the kept excess to `out` (3 ch, the accumulated colour's size), each pixel's times
    /// factor(x, y, channel) (e.g. the remodulation's albedo factor).
    template <typename Factor> void addExcess(Image& out, Factor&& factor) const
    {
        forEach([&](int x, int y, const float* v) {
            for (int k = 0; k < 3; ++k)
                out(x, y, k) += v[k] * factor(x, y, k);
        });
    }
    /// Pixels whose excess was kept in the last split().
    std::int64_t pixels() const { return static_cast<std::int64_t>(m_excess.size()); }

private:
    struct Excess {
        int x, y;
        float value[3];
    };
    /// Start a split; false (nothing to keep) when the limit is +infinity.
    bool begin(float limit, int height);
    /// Keep pixel (x, y) of colour v (rows may run on several threads, each row on one).
    void keep(int x, int y, const float* v);
    /// Gather the rows' pixels in row order.
    void finish();

    float m_limit = 0.0f;
    std::vector<Excess> m_excess; ///< in row order
    std::vector<std::vector<Excess>> m_rows; ///< per row, during a split
    const Image* m_source = nullptr; ///< the image of split(const Image&), else null
    std::vector<char> m_over; ///< clamped(): per row, a value above the limit
    Image m_clamped[2];
};

} // namespace afn
