// SPDX-License-Identifier: Apache-2.0
// Images inside the core: an owning interleaved float image and a non-owning strided view.
// Shared rules: row 0 is the top row; (x, y) index column and row; channels are interleaved.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace afn {

/// Non-owning view of a float image with `channels` interleaved channels and byte strides.
/// The row stride may be negative (bottom-up storage).
struct ImageView {
    const std::byte* base = nullptr; ///< address of pixel (0, 0), channel 0
    int width = 0;
    int height = 0;
    int channels = 0; ///< floats per pixel that are read
    std::ptrdiff_t pixelStride = 0; ///< bytes between horizontally adjacent pixels
    std::ptrdiff_t rowStride = 0; ///< bytes between vertically adjacent rows (may be < 0)

    bool empty() const { return base == nullptr || width <= 0 || height <= 0; }
    /// Pointer to the first channel of pixel (x, y).
    const float* at(int x, int y) const
    {
        return reinterpret_cast<const float*>(base + y * rowStride + x * pixelStride);
    }
    float* atMutable(int x, int y) const
    {
        return reinterpret_cast<float*>(
            const_cast<std::byte*>(base) + y * rowStride + x * pixelStride);
    }
};

/// Owning image: `width x height` pixels of `channels` interleaved floats, rows packed top-down.
class Image {
public:
    Image() = default;
    Image(int width, int height, int channels, float fill = 0.0f)
        : m_width(width)
        , m_height(height)
        , m_channels(channels)
        , m_data(static_cast<std::size_t>(width) * height * channels, fill)
    {
    }

    int width() const { return m_width; }
    int height() const { return m_height; }
    int channels() const { return m_channels; }
    bool empty() const { return m_data.empty(); }
    std::size_t size() const { return m_data.size(); }

    float* data() { return m_data.data(); }
    const float* data() const { return m_data.data(); }
    float* at(int x, int y)
    {
        return m_data.data() + (static_cast<std::size_t>(y) * m_width + x) * m_channels;
    }
    const float* at(int x, int y) const
    {
        return m_data.data() + (static_cast<std::size_t>(y) * m_width + x) * m_channels;
    }
    float& operator()(int x, int y, int c) { return at(x, y)[c]; }
    float operator()(int x, int y, int c) const { return at(x, y)[c]; }

    /// Reallocate only when the shape changes; contents are then unspecified (zero on growth).
    void resize(int width, int height, int channels)
    {
        if (width == m_width && height == m_height && channels == m_channels)
            return;
        m_width = width;
        m_height = height;
        m_channels = channels;
        m_data.assign(static_cast<std::size_t>(width) * height * channels, 0.0f);
    }
    /// As resize, for an image whose every value that is read will be written first: a change
    /// of shape keeps the allocation and the old values where the capacity suffices (no pass
    /// that zeroes the whole image; values past the old size are zero).
    void reshape(int width, int height, int channels)
    {
        const std::size_t n = static_cast<std::size_t>(width) * height * channels;
        if (n > m_data.capacity())
            m_data.reserve(n); // exactly n (resize alone may allocate up to twice the old size)
        m_width = width;
        m_height = height;
        m_channels = channels;
        m_data.resize(n);
    }
    void fill(float v) { m_data.assign(m_data.size(), v); }
    bool sameShape(const Image& o) const
    {
        return m_width == o.m_width && m_height == o.m_height && m_channels == o.m_channels;
    }

    /// A strided view of this image.
    ImageView view() const
    {
        ImageView v;
        v.base = reinterpret_cast<const std::byte*>(m_data.data());
        v.width = m_width;
        v.height = m_height;
        v.channels = m_channels;
        v.pixelStride = static_cast<std::ptrdiff_t>(m_channels * sizeof(float));
        v.rowStride = v.pixelStride * m_width;
        return v;
    }

private:
    int m_width = 0;
    int m_height = 0;
    int m_channels = 0;
    std::vector<float> m_data;
};

} // namespace afn
