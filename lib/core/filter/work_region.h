// SPDX-License-Identifier: Apache-2.0
// Rows of a work mask as bounding spans: per row, the half-open column range [x0, x1) that holds
// every pixel needing work (empty when x0 >= x1). Methods restrict their passes to such spans and
// dilate them by their footprint (a square dilation of the spans, so always a superset of the
// dilated mask: computing more pixels than needed never changes a needed one). A row whose
// needed pixels are far apart computes the columns between them too; a sky above or below the
// subject, an alpha-0 border and a rectangular user mask lose nothing.
#pragma once

#include "base/image.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace afn {

class WorkRegion {
public:
    WorkRegion() = default;
    /// Every pixel of a width x height frame.
    static WorkRegion full(int width, int height);
    /// The pixels where `work` (1 ch) is > 0.
    static WorkRegion fromMask(const Image& work);

    /// This region grown by `radius` pixels in x and y (clipped to the frame).
    WorkRegion dilated(int radius) const;
    /// The union of both regions' spans, row by row (same frame size).
    WorkRegion united(const WorkRegion& other) const;

    int width() const { return m_width; }
    int height() const { return static_cast<int>(m_rows.size()); }
    int x0(int y) const { return m_rows[y].first; }
    int x1(int y) const { return m_rows[y].second; }
    bool rowEmpty(int y) const { return m_rows[y].first >= m_rows[y].second; }
    /// True when any pixel of rectangle [x0, x1) x [y0, y1) (clipped to the frame) is inside.
    bool intersects(int x0, int y0, int x1, int y1) const;
    /// Number of pixels inside the spans.
    std::int64_t area() const;

private:
    int m_width = 0;
    std::vector<std::pair<int, int>> m_rows;
};

} // namespace afn
