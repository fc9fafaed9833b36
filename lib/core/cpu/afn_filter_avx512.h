// SPDX-License-Identifier: Apache-2.0
// AVX-512 softmax + 7x7 kernel application of AFN's fused filtering pass (cpu/afn_fusion.cpp),
// used where cpu::activeIsa() is Avx512: 16 pixels of a row at a time, one pixel per lane.
#pragma once

#include "base/image.h"

#include <vector>

namespace afn::cpu {

/// Eight rows of a 3-channel image, channel-planar, with 3 zero pixels left and right and zero
/// rows above and below the image: row yy lives in slot yy & 7, so any 7 or 8 consecutive rows
/// are held at once and moving down one or two rows converts only the new ones. The image may be
/// a window of the frame (AFN stripes): rows outside it are zero (methods/afn/fusion.h).
class PlanarRows {
public:
    /// Start over for `img` (its contents may have changed).
    void reset(const Image& img);
    /// Make row yy resident (converted if its slot holds another row).
    void ensure(int yy);
    /// Channel c of row yy (must be resident), pixel x at index x (x from -3; 16 zero floats of
    /// slack after the last pixel's 3-pixel pad).
    const float* plane(int yy, int c) const;

private:
    const Image* m_img = nullptr;
    int m_stride = 0; ///< floats per plane
    int m_slotRow[8] = {};
    std::vector<float> m_buf;
};

/// Softmax (methods/afn/fusion.h semantics: non-finite logits made finite, maximum subtracted)
/// over the 49 logits of each of n <= 16 pixels x0 .. x0 + n - 1 of row y, pixel p's logits at
/// logits + p * stride, then its normalised 7x7 kernel applied to the image `rows` holds (rows
/// y - 3 .. y + 3 resident). Pixel p's filtered colour is written to rgb + 3 p. `bf16Logits`: the
/// heads ran in bf16; a cheaper exponential then serves (cpu/afn_filter_avx512.cpp).
void softmaxApplyRowAvx512(const float* logits, int stride, int n, const PlanarRows& rows, int x0,
    int y, float* rgb, bool bf16Logits = false);

} // namespace afn::cpu
