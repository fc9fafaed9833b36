// SPDX-License-Identifier: Apache-2.0
// Host images addressed through their bounds: fetching and releasing (RAII), describing a window
// as a top-down strided buffer for afnSetFilterImage, and writing a tile of a result into one.
#pragma once

#include "ofx/ofx_api.h"

#include <cstddef>
#include <vector>

namespace afnofx {

/// An image fetched with clipGetImage, released on destruction.
class ClipImage {
public:
    /// Fetch the clip's image at `time` (region in canonical coordinates, NULL = whole).
    /// Leaves the image invalid when the host has none (e.g. before the clip's first frame).
    ClipImage(OfxImageClipHandle clip, double time, const OfxRectD* region = nullptr);
    ~ClipImage();
    ClipImage(const ClipImage&) = delete;
    ClipImage& operator=(const ClipImage&) = delete;

    bool valid() const { return m_handle != nullptr && m_data != nullptr; }
    int components() const { return m_components; }
    const OfxRectI& bounds() const { return m_bounds; }
    /// Address of pixel (x, y) in OFX pixel coordinates (y up, relative to nothing: bounds
    /// decide where the data pointer is). (x, y) must lie inside bounds().
    float* pixel(int x, int y) const;

private:
    OfxPropertySetHandle m_handle = nullptr;
    char* m_data = nullptr;
    OfxRectI m_bounds {};
    int m_rowBytes = 0;
    int m_components = 0;
};

/// A window of an image described top-down for the library (row 0 = top row of the window).
struct StridedView {
    void* ptr = nullptr;
    size_t pixelStride = 0; ///< bytes
    ptrdiff_t rowStride = 0; ///< bytes; negative host row bytes come out positive and vice versa
    int components = 0;
};

/// View `window` of `image` zero-copy when its bounds cover the window; otherwise copy the
/// overlapping pixels into `scratch` (zeros elsewhere) and view that.
StridedView viewWindow(const ClipImage& image, const OfxRectI& window, std::vector<float>& scratch);

/// Write the pixels of `dst`'s `renderWindow` from a packed top-down RGBA frame covering `frame`
/// (zeros outside it). With a `source` image, write mix * frame + (1 - mix) * source instead
/// (source zero outside its bounds; an RGB source leaves the frame's alpha). Rows are split
/// across the host's threads when it offers them.
void writeTile(const ClipImage& dst, const OfxRectI& renderWindow, const float* frameRgba,
    const OfxRectI& frame, const ClipImage* source = nullptr, float mix = 1.0f);

} // namespace afnofx
