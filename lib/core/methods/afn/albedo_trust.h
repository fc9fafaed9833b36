// SPDX-License-Identifier: Apache-2.0
// afn's learned albedo trust (weights with albedoTrust=1; training/afn/model.py, ``albedo_trust``,
// is the definition and gives the reasoning). Per half-resolution pixel the network predicts
//   t = sigmoid(headG(e1))            3x3 conv on the first encoder level, 16 -> 1
// the share of colour-space filtering there, and the filtering runs on the colour demodulated by
//   a' = a + (1 - a) * U(t)           per channel; a = the demodulation albedo (x's channels 6-8)
// instead of by a: both colour inputs are multiplied by s = max(a, eps) / max(a', eps) before the
// filtering (the 1-spp one before its pooling), and the network's output is divided by s, so it
// stays in the albedo-demodulated space the remodulation outside expects (which then gives
// o * max(a', eps)). t = 0 is the paper's demodulation; t = 1 filters the colour itself, the
// albedo and normal guiding the kernels only: where the renderer's albedo is noise (glass,
// mirrors, metal under depth of field or motion blur) the network can stop dividing by it.
// Rows are independent, so the stripes (network_stripes.cpp) and the whole-frame path compute
// the same values.
#pragma once

#include "base/image.h"
#include "nn/conv.h"

namespace afn::afnet {

/// Rows [y0, y1) of t (half resolution, 1 ch, already of e1's size: rows run on several threads)
/// from e1 (ReLU applied).
void albedoTrustRows(const nn::Conv& headG, const Image& e1, int y0, int y1, Image& t);

/// Multiply full-resolution rows [y0, y1) of `color` (3 ch) by s; the albedo is channels 6-8 of
/// `x` (the network input, same rows), t the half-resolution share (row y reads row y / 2).
void applyAlbedoTrustRows(const Image& x, const Image& t, int y0, int y1, Image& color);

/// Divide full-resolution rows [y0, y1) of an output by s: row y at dst + (y - y0) * dstRow,
/// its first `width` RGB pixels (at most x.width()); x and t as above (rows in their own
/// numbering).
void undoAlbedoTrustRows(
    const Image& x, const Image& t, int y0, int y1, int width, float* dst, long dstRow);

} // namespace afn::afnet
