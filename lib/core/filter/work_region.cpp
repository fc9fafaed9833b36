// SPDX-License-Identifier: Apache-2.0
#include "filter/work_region.h"

#include <algorithm>

namespace afn {

WorkRegion WorkRegion::full(int width, int height)
{
    WorkRegion r;
    r.m_width = width;
    r.m_rows.assign(static_cast<std::size_t>(std::max(height, 0)), { 0, width });
    return r;
}

WorkRegion WorkRegion::fromMask(const Image& work)
{
    WorkRegion r;
    r.m_width = work.width();
    r.m_rows.assign(static_cast<std::size_t>(work.height()), { 0, 0 });
    for (int y = 0; y < work.height(); ++y) {
        const float* row = work.at(0, y);
        int first = -1, last = -1;
        for (int x = 0; x < work.width(); ++x)
            if (row[x] > 0.0f) {
                if (first < 0)
                    first = x;
                last = x;
            }
        if (first >= 0)
            r.m_rows[y] = { first, last + 1 };
    }
    return r;
}

WorkRegion WorkRegion::dilated(int radius) const
{
    WorkRegion r;
    r.m_width = m_width;
    const int h = height();
    r.m_rows.assign(m_rows.size(), { 0, 0 });
    for (int y = 0; y < h; ++y) {
        int lo = m_width, hi = 0;
        for (int q = std::max(0, y - radius); q <= std::min(h - 1, y + radius); ++q)
            if (!rowEmpty(q)) {
                lo = std::min(lo, m_rows[q].first);
                hi = std::max(hi, m_rows[q].second);
            }
        if (lo < hi)
            r.m_rows[y] = { std::max(0, lo - radius), std::min(m_width, hi + radius) };
    }
    return r;
}

WorkRegion WorkRegion::united(const WorkRegion& o) const
{
    WorkRegion r = *this;
    for (int y = 0; y < height() && y < o.height(); ++y) {
        if (o.rowEmpty(y))
            continue;
        if (rowEmpty(y))
            r.m_rows[y] = o.m_rows[y];
        else
            r.m_rows[y] = { std::min(x0(y), o.x0(y)), std::max(x1(y), o.x1(y)) };
    }
    return r;
}

bool WorkRegion::intersects(int x0, int y0, int x1, int y1) const
{
    for (int y = std::max(0, y0); y < std::min(height(), y1); ++y)
        if (!rowEmpty(y) && m_rows[y].first < x1 && m_rows[y].second > x0)
            return true;
    return false;
}

std::int64_t WorkRegion::area() const
{
    std::int64_t n = 0;
    for (const auto& [a, b] : m_rows)
        n += std::max(0, b - a);
    return n;
}

} // namespace afn
