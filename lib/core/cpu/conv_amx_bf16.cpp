// SPDX-License-Identifier: Apache-2.0
// nn::Conv's bfloat16 layers on AMX tiles (TDPBF16PS): an implicit GEMM over the bf16 band that
// cpu/conv_avx512_bf16.cpp builds (pixels (H, W, C), C a multiple of 16, zero halo and slack).
//
// Per tap (ky, kx) and per chunk of 32 input channels (16 where C is not a multiple of 32), an A
// tile holds 16 consecutive output pixels' input channels (one pixel per tile row: rows 2 C bytes
// apart in the band) and a B tile the tap's weights for those channel pairs x 16 output channels
// (ConvArgs::wamx, pairs padded with zero rows to C / 2 per tap, so every chunk is a whole tile). A
// C tile sums 16 pixels x 16 output channels in fp32. Eight tiles: C0..C3 = 2 pixel blocks x 2
// output groups, A4/A5 the two pixel blocks, B6/B7 the two output groups; each A tile is used by
// two products and each B tile by two. Layers with more than 32 output channels repeat the taps per
// pair of groups.
//
// Arithmetic: products of bf16 values summed in fp32 from zero, the bias added at the end, then
// ReLU. The instruction's summation order inside a tile product is the hardware's (not
// VDPBF16PS's), and it flushes denormal inputs and results: the outputs agree with the other bf16
// kernels within fp32 summation error, not bit for bit (tests/unit/core/nn/test_conv_bf16.cpp).
// Output pixels of a block past the row's end read band values that belong to the next row or to
// the slack, and are never stored.
#include "cpu/conv_amx_bf16.h"

#include "cpu/avx512.h"

#include <algorithm>

namespace afn::cpu {

#ifdef AFN_CPU_HAVE_AVX512

#define AFN_CPU_AMX __attribute__((target("amx-tile,amx-bf16,avx512f,avx512bw,avx2,fma")))

namespace {

/// The 64-byte LDTILECFG operand (palette 1).
struct alignas(64) TileConfig {
    std::uint8_t palette = 1;
    std::uint8_t startRow = 0;
    std::uint8_t reserved[14] = {};
    std::uint16_t colsb[16] = {};
    std::uint8_t rows[16] = {};
};
static_assert(sizeof(TileConfig) == 64);

constexpr int kBlock = 16; ///< output pixels per tile (tile rows)

/// Tiles for chunks of `chunk` input channels (16 or 32: an A tile row of 32 or 64 bytes).
TileConfig tileConfig(int chunk)
{
    TileConfig t;
    for (int i = 0; i < 4; ++i) { // C: 16 pixels x 16 fp32
        t.rows[i] = kBlock;
        t.colsb[i] = 64;
    }
    for (int i = 4; i < 6; ++i) { // A: 16 pixels x chunk bf16
        t.rows[i] = kBlock;
        t.colsb[i] = static_cast<std::uint16_t>(chunk * 2);
    }
    for (int i = 6; i < 8; ++i) { // B: chunk / 2 pairs x 16 outputs x 2 bf16
        t.rows[i] = static_cast<std::uint8_t>(chunk / 2);
        t.colsb[i] = 64;
    }
    return t;
}

/// Bias, ReLU and the masked store of one C tile's sums (np pixels, output group g).
AFN_CPU_AVX512_INLINE void storeTile(
    const AmxConvPass& p, const float (&sums)[kBlock][16], float* dst, int np, int g)
{
    const int n = std::min(16, p.outC - 16 * g);
    if (n <= 0)
        return;
    const __mmask16 mask = firstLanes(n);
    const __m512 bias = _mm512_loadu_ps(p.bias + 16 * g);
    const __m512 zero = _mm512_setzero_ps();
    for (int i = 0; i < np; ++i) {
        __m512 v = _mm512_add_ps(_mm512_load_ps(sums[i]), bias);
        if (p.relu)
            v = _mm512_max_ps(v, zero);
        _mm512_mask_storeu_ps(dst + static_cast<long>(i) * p.pixStride + 16 * g, mask, v);
    }
}

} // namespace

AFN_CPU_AMX void convRowsAmxBf16(const AmxConvPass& p, int nRows)
{
    // Chunks of 32 channels where the band's channels allow, else 16 (C = 16, 48, 80...).
    static const TileConfig config16 = tileConfig(16), config32 = tileConfig(32);
    const int chunk = p.c % 32 == 0 ? 32 : 16;
    _tile_loadconfig(chunk == 32 ? &config32 : &config16);
    alignas(64) float sums[4][kBlock][16];
    const long aStride = 2L * p.c; // bytes from one pixel to the next in the band
    const long bStride = 4L * p.cp16; // bytes from one pair of input channels to the next
    const int chunks = p.c / chunk, groups = p.cp16 / 16;
    for (int row = 0; row < nRows; ++row) {
        const std::uint16_t* src = p.band + row * p.bandRow;
        float* dst = p.dst + row * p.dstRow;
        for (int x = 0; x < p.width; x += 2 * kBlock) {
            const bool two = x + kBlock < p.width;
            for (int g = 0; g < groups; g += 2) {
                const bool g2 = g + 1 < groups;
                _tile_zero(0);
                _tile_zero(1);
                _tile_zero(2);
                _tile_zero(3);
                for (int ky = 0; ky < p.k; ++ky)
                    for (int kx = 0; kx < p.k; ++kx) {
                        const std::uint16_t* a
                            = src + ky * p.bandRow + static_cast<long>(x + kx) * p.c;
                        const std::uint16_t* b = p.w
                            + (static_cast<long>(ky * p.k + kx) * (p.c / 2) * p.cp16 + 16 * g) * 2;
                        for (int ch = 0; ch < chunks; ++ch) {
                            const std::uint16_t* ac = a + ch * chunk;
                            const std::uint16_t* bc
                                = b + static_cast<long>(ch) * (chunk / 2) * p.cp16 * 2;
                            _tile_loadd(4, ac, aStride);
                            _tile_loadd(6, bc, bStride);
                            _tile_dpbf16ps(0, 4, 6);
                            if (two) {
                                _tile_loadd(5, ac + kBlock * p.c, aStride);
                                _tile_dpbf16ps(2, 5, 6);
                            }
                            if (g2) {
                                _tile_loadd(7, bc + 32, bStride);
                                _tile_dpbf16ps(1, 4, 7);
                                if (two)
                                    _tile_dpbf16ps(3, 5, 7);
                            }
                        }
                    }
                _tile_stored(0, sums[0], 64);
                _tile_stored(1, sums[1], 64);
                _tile_stored(2, sums[2], 64);
                _tile_stored(3, sums[3], 64);
                float* d = dst + static_cast<long>(x) * p.pixStride;
                const int np0 = std::min(kBlock, p.width - x);
                storeTile(p, sums[0], d, np0, g);
                if (g2)
                    storeTile(p, sums[1], d, np0, g + 1);
                if (two) {
                    float* d1 = d + static_cast<long>(kBlock) * p.pixStride;
                    const int np1 = std::min(kBlock, p.width - x - kBlock);
                    storeTile(p, sums[2], d1, np1, g);
                    if (g2)
                        storeTile(p, sums[3], d1, np1, g + 1);
                }
            }
        }
    }
    _tile_release();
}

#else

void convRowsAmxBf16(const AmxConvPass&, int) { }

#endif

} // namespace afn::cpu
