// SPDX-License-Identifier: Apache-2.0
// Structure-of-arrays float planes for SVGF's vectorised kernels (methods/svgf/kernels.h).
// Every row of every plane has kPlanePad zero floats on both sides and its width rounded up to a
// multiple of kLanes, so 8 lanes starting anywhere in [x - kPlanePad, x + kPlanePad] for an x of
// the image load without a bounds check. The kernels write only in-image pixels: padding stays 0
// (finite), so a masked-out lane times a zero weight stays 0.
#pragma once

#include <cstddef>
#include <vector>

namespace afn::svgf {

/// Lanes of the kernels' vectors.
constexpr int kLanes = 8;
/// Zero floats left and right of every row: the 5x5 taps of steps up to 16 (5 iterations) and the
/// 7x7 variance estimate load directly; larger offsets take a per-lane path.
constexpr int kPlanePad = 32;

/// `count` planes of width x height floats.
class Planes {
public:
    /// Reallocate (zero-filled) when the shape changes; otherwise keep the contents.
    void resize(int width, int height, int count)
    {
        if (width == m_width && height == m_height && count == m_count)
            return;
        m_width = width;
        m_height = height;
        m_count = count;
        m_stride = kPlanePad + (width + kLanes - 1) / kLanes * kLanes + kPlanePad;
        m_data.assign(static_cast<std::size_t>(m_stride) * height * count, 0.0f);
    }
    int width() const { return m_width; }
    int height() const { return m_height; }
    int count() const { return m_count; }
    /// Floats from pixel x to pixel x of the next row.
    int stride() const { return m_stride; }
    /// Pixel 0 of row y of plane `plane`.
    float* row(int plane, int y)
    {
        return m_data.data() + (static_cast<std::size_t>(plane) * m_height + y) * m_stride
            + kPlanePad;
    }
    const float* row(int plane, int y) const
    {
        return m_data.data() + (static_cast<std::size_t>(plane) * m_height + y) * m_stride
            + kPlanePad;
    }

private:
    int m_width = 0, m_height = 0, m_count = 0, m_stride = 0;
    std::vector<float> m_data;
};

} // namespace afn::svgf
