// SPDX-License-Identifier: Apache-2.0
// Highlights that bypass a spatial filter (see stages/highlight_bypass.h).
#include "stages/highlight_bypass.h"

#include "base/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace afn {

namespace {

constexpr double kQuantile = 0.99; ///< the 99th of 100 samples (0.99f would round up)
/// Exponents of the histogram: values of 2^(kLowest - 1) or less (and 0) count in bin 0.
constexpr int kLowest = -64, kHighest = 64, kBins = kHighest - kLowest + 1;

/// Bin of v: e - kLowest for v in [2^(e-1), 2^e) (std::frexp), clamped to the histogram.
int binOf(float v)
{
    if (!(v > 0.0f))
        return 0;
    int e = 0;
    std::frexp(v, &e);
    return std::clamp(e, kLowest, kHighest) - kLowest;
}

} // namespace

float highlightLimit(int w, int h, float factor, const std::function<float(int, int)>& largest)
{
    if (!(factor > 0.0f) || w <= 0 || h <= 0)
        return std::numeric_limits<float>::infinity();
    std::array<std::int64_t, kBins> counts {};
    std::int64_t n = 0;
    for (int y = 0; y < h; y += kHighlightStride)
        for (int x = 0; x < w; x += kHighlightStride, ++n)
            ++counts[binOf(largest(x, y))];
    // The smallest bin whose cumulative count reaches the quantile: its upper edge 2^e.
    const auto target = static_cast<std::int64_t>(std::ceil(kQuantile * static_cast<double>(n)));
    std::int64_t below = 0;
    int bin = 0;
    for (; bin < kBins - 1; ++bin) {
        below += counts[bin];
        if (below >= target)
            break;
    }
    return factor * std::ldexp(1.0f, bin + kLowest);
}

float highlightLimit(const Image& acc, float factor)
{
    if (acc.empty())
        return std::numeric_limits<float>::infinity();
    return highlightLimit(acc.width(), acc.height(), factor, [&](int x, int y) {
        const float* p = acc.at(x, y);
        return std::max({ p[0], p[1], p[2] });
    });
}

bool HighlightBypass::begin(float limit, int height)
{
    m_source = nullptr;
    m_limit = limit;
    m_excess.clear();
    if (std::isinf(limit))
        return false;
    m_rows.resize(static_cast<std::size_t>(height));
    for (auto& r : m_rows)
        r.clear();
    return true;
}

void HighlightBypass::keep(int x, int y, const float* v)
{
    Excess e { x, y, {} };
    for (int k = 0; k < 3; ++k)
        e.value[k] = std::max(v[k] - m_limit, 0.0f);
    m_rows[static_cast<std::size_t>(y)].push_back(e);
}

void HighlightBypass::finish()
{
    for (const auto& r : m_rows)
        m_excess.insert(m_excess.end(), r.begin(), r.end());
}

void HighlightBypass::split(const Image& acc, float limit)
{
    const int w = acc.width();
    split(w, acc.height(), limit, [&](int x, int y, int k) { return acc.at(0, y)[3 * x + k]; });
    m_source = &acc;
}

const Image& HighlightBypass::clamped(const Image& img, int slot)
{
    // Nothing to clamp: the limit is off, or the split's own image had no value above it (its
    // kept pixels say so), or no value of `img` is above it.
    if (std::isinf(m_limit) || (&img == m_source && m_excess.empty()))
        return img;
    const float limit = m_limit;
    const int h = img.height();
    const std::size_t row = static_cast<std::size_t>(img.width()) * img.channels();
    if (&img != m_source) {
        m_over.assign(static_cast<std::size_t>(h), 0);
        parallelRows(h, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y) {
                const float* s = img.at(0, y);
                m_over[static_cast<std::size_t>(y)]
                    = std::any_of(s, s + row, [limit](float v) { return v > limit; });
            }
        });
        if (std::none_of(m_over.begin(), m_over.end(), [](char c) { return c != 0; }))
            return img;
    }
    Image& out = m_clamped[slot];
    out.resize(img.width(), img.height(), img.channels());
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const float* s = img.at(0, y);
            float* d = out.at(0, y);
            for (std::size_t i = 0; i < row; ++i)
                d[i] = std::min(s[i], limit);
        }
    });
    return out;
}

} // namespace afn
