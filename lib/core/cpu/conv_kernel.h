// SPDX-License-Identifier: Apache-2.0
// The CPU kernel of nn::Conv: direct k x k convolution rows over interleaved (H, W, C) images,
// 4 output pixels x 8 output channels per micro-kernel step (register blocking).
#pragma once

#include "base/image.h"

#include <cstdint>
#include <vector>

namespace afn::cpu {

/// Most output channels of a layer that the AVX-512 code runs with input channels in the lanes.
constexpr int kFewOutputs = 4;

/// One convolution's operands (see nn::Conv::run for the meaning of `up` and `same`).
struct ConvArgs {
    const Image* up; ///< half-size input read through nearest 2x upsampling, or null
    const Image* same; ///< full-size input
    const float* wp; ///< weights [ky][kx][ci][cp]
    const float* bp; ///< bias [cp]
    int in, k, cp, outC, nu, ns;
    bool relu;
    const float* wp16 = nullptr; ///< weights [ky][kx][ci][cp16] (AVX-512 kernels)
    const float* bp16 = nullptr; ///< bias [cp16]
    int cp16 = 0; ///< output channels rounded up to 16
    /// Layers of at most kFewOutputs output channels: weights [ky][kx][co][ci padded to 16] for
    /// the AVX-512 kernel that puts input channels in the lanes (null for other layers).
    const float* wt16 = nullptr;
    float* dst = nullptr; ///< output row dstY0 (outC channels of each pixel are written)
    long dstRow = 0; ///< floats from one output row to the next
    int dstPix = 0; ///< floats from one output pixel to the next (>= outC)
    int dstY0 = 0; ///< the row that dst points to
    /// Output columns [x0, x1) (x1 < 0: to the width); dst points to column x0 of row dstY0.
    int x0 = 0, x1 = -1;
    /// bfloat16 weights [ky][kx][ci pair][cp16][2] (ci even in the low half of each 32-bit pair):
    /// where set (AVX-512 engine only), convRowsAvx512 runs the layer in bf16 with fp32
    /// accumulation (cpu/conv_avx512_bf16.cpp).
    const std::uint16_t* wbf16 = nullptr;
    /// The same weights with each tap's pairs padded with zeros to c / 2, c = the input channels
    /// rounded up to 16 (the band's channels): the AMX kernel's B tiles (cpu/conv_amx_bf16.h).
    /// Set with wbf16 where the CPU can run AMX.
    const std::uint16_t* wamx = nullptr;
    /// Layers of at most kFewOutputs outputs in bf16 (cpu/conv_few_outputs_bf16.cpp): weights
    /// [ky][co][kx][ci padded to bandChannels(in)], each (ky, co) run padded with zeros to
    /// fewOutputsChunks(k, in) x 32 values. Where set, convRowsAvx512 runs the layer in bf16.
    const std::uint16_t* wtbf16 = nullptr;
};

/// 32-value vectors of one kernel row of a few-output layer's bf16 weights (ConvArgs::wtbf16).
inline int fewOutputsChunks(int k, int in)
{
    return (k * ((in + 15) / 16 * 16) + 31) / 32;
}

/// Channels of a band pixel: the layer's input channels rounded up to 16 (one AVX-512 vector; even,
/// so bf16 channel pairs never straddle two pixels).
inline int bandChannels(int in)
{
    return (in + 15) / 16 * 16;
}

/// The end of ConvArgs' output columns (x1, or the input's width where x1 < 0).
inline int columnEnd(const ConvArgs& a)
{
    return a.x1 < 0 ? a.same->width() : a.x1;
}

/// Where a band's rows [y0 - k/2, y1 + k/2) take their pixels from (fillConvBandAvx512 and its
/// bf16 twin): `bw` pixels a row, of which input columns [xa, xb) after `lead` zero pixels and
/// before `trail` more; input rows outside [0, h) are zero rows.
struct ConvBandGeometry {
    int h, r, bw, xa, xb, lead, trail, rows;
};

inline ConvBandGeometry convBandGeometry(const ConvArgs& a, int y0, int y1)
{
    const int w = a.same->width(), r = a.k / 2;
    const int x0 = a.x0, x1 = columnEnd(a);
    const int xa = x0 - r < 0 ? 0 : x0 - r, xb = x1 + r > w ? w : x1 + r;
    return { a.same->height(), r, x1 - x0 + 2 * r, xa, xb, xa - (x0 - r), x1 + r - xb,
        y1 - y0 + 2 * r };
}

/// Output rows [y0, y1) with the portable kernel.
void convRows(const ConvArgs& a, int y0, int y1);

/// Output rows [y0, y1) with the AVX-512 micro-kernels (cpu/conv_avx512.cpp; call only where
/// activeIsa() is Avx512). Layers with `wbf16` or `wtbf16` run convRowsAvx512Bf16.
void convRowsAvx512(const ConvArgs& a, int y0, int y1);

/// The same in bfloat16 (cpu/conv_avx512_bf16.cpp; activeBf16Mode() picks VDPBF16PS or its
/// emulation): the band's values and the weights rounded to bf16, products summed in fp32.
void convRowsAvx512Bf16(const ConvArgs& a, int y0, int y1);

/// Band rows [y0 - k/2, y1 + k/2) of concat(U(up), same) for output columns [x0, x1): (x1 - x0
/// + 2 (k/2)) pixels of `c` floats (channels zero-padded to c, a multiple of 16), zero outside the
/// image, then (kConvBandSlackPixels + 2) x c zero floats (cpu/conv_avx512.cpp).
void fillConvBandAvx512(const ConvArgs& a, int y0, int y1, int c, std::vector<float>& band);

/// The same band in bf16 (rounded to nearest even by the hardware, value by value), written
/// directly where the CPU has AVX512_BF16 (cpu/conv_band_bf16.cpp): at `d`, the band's values
/// (rows x pixels x c), zeros up to the next multiple of 32 values, then `slack` zeros. Returns
/// false, writing nothing, for band pixels wider than 256 channels.
bool fillConvBandBf16Avx512(
    const ConvArgs& a, int y0, int y1, int c, std::uint16_t* d, std::size_t slack);

/// Output rows [y0, y1) of a layer with `wtbf16` from its bf16 band (rows [y0 - k/2, y1 + k/2),
/// as fillConvBandBf16Avx512 writes it, with the slack): VDPBF16PS where `hardware`, else its
/// AVX-512F emulation with the same bits (cpu/conv_few_outputs_bf16.cpp).
void fewOutputsRowsBf16(
    const ConvArgs& a, const std::uint16_t* band, int y0, int y1, bool hardware);

/// The calling thread's band buffer, shared by the fp32 and bf16 kernels (each call refills it;
/// the bf16 kernel rounds it in place): one buffer per thread, the size of the largest band.
std::vector<float>& convBandBuffer();

/// Most pixels a micro-kernel block reads past a band row's end (the band's zeroed slack).
constexpr int kConvBandSlackPixels = 16;

/// Output rows per band of the AVX-512 kernels: a band (its rows plus the k/2-row halos, fp32)
/// of about 512 KB, so that it is filled, (rounded to bf16) and read by the kernel while it is in
/// the core's L2 cache; a band of a whole stripe is megabytes (64 rows x 1280 pixels x 64
/// channels: 21 MB). The halo rows are filled once per band; the outputs do not depend on it.
inline int bandRowGroup(const ConvArgs& a)
{
    constexpr long kBandBytes = 512 * 1024;
    const int r = a.k / 2;
    const long rowBytes = static_cast<long>(columnEnd(a) - a.x0 + 2 * r) * bandChannels(a.in) * 4;
    const long group = kBandBytes / rowBytes - 2 * r;
    return group < 1 ? 1 : static_cast<int>(group);
}

} // namespace afn::cpu
