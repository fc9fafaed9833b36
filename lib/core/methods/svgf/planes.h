// SPDX-License-Identifier: Apache-2.0
// Structure-of-arrays float planes for SVGF's vectorised kernels (methods/svgf/kernels.h).
// Every row of every plane has kPlanePad zero floats on both sides and its width rounded up to a
// multiple of kRowAlign, so 8 lanes starting anywhere in [x - kPlanePad, x + kPlanePad] for an x of
// the image load without a bounds check. Pixel 0 of every row starts a 64-byte cache line, so the
// AVX-512 kernels' 16-pixel vectors at x = 0, 16, 32, ... (and their taps at multiples of 16
// pixels) load one line, not two (docs/performance.md). The kernels write only
// in-image pixels: padding stays 0 (finite), so a masked-out lane times a zero weight stays 0.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace afn::svgf {

/// Lanes of the kernels' vectors.
constexpr int kLanes = 8;
/// Zero floats left and right of every row: the 5x5 taps of steps up to 16 (5 iterations) and the
/// 7x7 variance estimate load directly; larger offsets take a per-lane path.
constexpr int kPlanePad = 32;
/// Floats per 64-byte cache line: row strides and the planes' start are multiples of it.
constexpr int kRowAlign = 16;

/// `count` planes of width x height floats.
class Planes {
public:
    Planes() = default;
    // Moves keep the buffer (so its alignment); a copy would not, and none is needed.
    Planes(const Planes&) = delete;
    Planes& operator=(const Planes&) = delete;
    Planes(Planes&&) noexcept = default;
    Planes& operator=(Planes&&) noexcept = default;

    /// Reallocate (zero-filled) when the shape changes; otherwise keep the contents.
    void resize(int width, int height, int count)
    {
        if (width == m_width && height == m_height && count == m_count)
            return;
        m_width = width;
        m_height = height;
        m_count = count;
        m_stride = kPlanePad + (width + kRowAlign - 1) / kRowAlign * kRowAlign + kPlanePad;
        m_data.assign(static_cast<std::size_t>(m_stride) * height * count + kRowAlign, 0.0f);
        // The first float on a 64-byte boundary (the vector's own is 16-byte aligned).
        const auto address = reinterpret_cast<std::uintptr_t>(m_data.data());
        m_offset = static_cast<std::size_t>((64 - address % 64) % 64 / sizeof(float));
    }
    int width() const { return m_width; }
    int height() const { return m_height; }
    int count() const { return m_count; }
    /// Floats from pixel x to pixel x of the next row.
    int stride() const { return m_stride; }
    /// Pixel 0 of row y of plane `plane`.
    float* row(int plane, int y)
    {
        return m_data.data() + m_offset
            + (static_cast<std::size_t>(plane) * m_height + y) * m_stride + kPlanePad;
    }
    const float* row(int plane, int y) const
    {
        return m_data.data() + m_offset
            + (static_cast<std::size_t>(plane) * m_height + y) * m_stride + kPlanePad;
    }

private:
    int m_width = 0, m_height = 0, m_count = 0, m_stride = 0;
    std::size_t m_offset = 0; ///< floats from m_data's start to the first aligned one
    std::vector<float> m_data;
};

} // namespace afn::svgf
