// SPDX-License-Identifier: Apache-2.0
// The AMX micro-kernel of nn::Conv's bfloat16 engine (cpu/conv_avx512_bf16.cpp builds the band and
// calls it where cpu::activeBf16Mode() is Amx).
#pragma once

#include <cstdint>

namespace afn::cpu {

/// Operands of the AMX pass over rows of one band (all output channels of the layer).
struct AmxConvPass {
    const std::uint16_t* band; ///< bf16 band, pixel -r of the band row of output row 0
    long bandRow; ///< bf16 values per band row
    int c; ///< channels per band pixel (a multiple of 16)
    const std::uint16_t* w; ///< ConvArgs::wamx: [tap][c / 2 pairs][cp16][2]
    const float* bias; ///< [cp16]
    int k, cp16, outC, width, pixStride;
    bool relu;
    float* dst; ///< output row 0, column 0
    long dstRow;
};

/// Output rows [0, nRows) of the pass: the band's rows are output rows plus the k/2 halo.
/// The last block of a row reads up to 15 pixels past the band row's end: the band must be followed
/// by that many zeroed pixels (its slack, cpu/conv_kernel.h).
void convRowsAmxBf16(const AmxConvPass& p, int nRows);

} // namespace afn::cpu
