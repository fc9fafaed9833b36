// SPDX-License-Identifier: Apache-2.0
// bfloat16 micro-kernels of nn::Conv (cpu/conv_kernel.h, ConvArgs::wbf16): the AFN network's
// reduced-precision engine (methods/afn/settings.h, precision).
//
// The layout of cpu/conv_avx512.cpp (implicit GEMM over a zero-padded input band, P output pixels
// x NV vectors of 16 output channels in registers) with the K dimension in pairs of input
// channels: the band is converted to bf16 once per task (round to nearest even), so one 32-bit
// broadcast carries channels (2q, 2q + 1) of a pixel, and one 512-bit weight vector carries 16
// output channels x that pair. VDPBF16PS then does two multiply-adds per lane: half the
// instructions of fp32 for the same work. Products of two bf16 values are exact in fp32; the sums
// are fp32, in the order bias, taps (ky, kx), pairs q, and within a pair channel 2q + 1 then 2q
// (the instruction's order), independent of how rows are split among threads.
//
// Where the CPU runs AMX (cpu::activeBf16Mode() Amx) the same band goes to the tile kernel
// (cpu/conv_amx_bf16.cpp) instead of these micro-kernels.
//
// Without AVX512_BF16 (cpu::activeBf16Mode() Emulated) the same arithmetic runs with AVX-512F:
// each bf16 half widened to fp32 by a shift or a mask, two FMAs per pair in the instruction's
// order. The results are the same bit for bit (the hardware flushes denormal inputs and results,
// which the emulation does not: a difference only for values below 1e-38); the speed is fp32's.
#include "cpu/conv_kernel.h"

#include "cpu/avx512.h"
#include "cpu/conv_amx_bf16.h"
#include "cpu/isa.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace afn::cpu {

namespace {

#ifdef AFN_CPU_HAVE_AVX512

/// The fp32 band converted to bf16 pairs: `n` floats (a multiple of 32) from s to d.
AFN_CPU_AVX512_BF16 void toBf16Hardware(std::uint16_t* d, const float* s, std::size_t n)
{
    for (std::size_t k = 0; k < n; k += 32) {
        const __m512bh v = _mm512_cvtne2ps_pbh(_mm512_loadu_ps(s + k + 16), _mm512_loadu_ps(s + k));
        _mm512_storeu_si512(d + k, reinterpret_cast<const __m512i&>(v));
    }
}

/// 16 floats (as bits) rounded to bf16 (to nearest even, NaN kept quiet) with AVX-512F.
AFN_CPU_AVX512_INLINE __m256i roundToBf16(__m512i u)
{
    const __m512i expMask = _mm512_set1_epi32(0x7F800000), manMask = _mm512_set1_epi32(0x007FFFFF);
    const __mmask16 nan = _mm512_cmpeq_epi32_mask(_mm512_and_si512(u, expMask), expMask)
        & _mm512_cmpneq_epi32_mask(_mm512_and_si512(u, manMask), _mm512_setzero_si512());
    const __m512i lsb = _mm512_and_si512(_mm512_srli_epi32(u, 16), _mm512_set1_epi32(1));
    const __m512i rounded = _mm512_add_epi32(u, _mm512_add_epi32(_mm512_set1_epi32(0x7FFF), lsb));
    u = _mm512_mask_mov_epi32(rounded, nan, _mm512_or_si512(u, _mm512_set1_epi32(0x00400000)));
    return _mm512_cvtepi32_epi16(_mm512_srli_epi32(u, 16));
}

/// The same rounding as toBf16Hardware with AVX-512F integer operations, 32 floats loaded before
/// their 64 bytes are stored, as the hardware conversion does (the in-place conversion's rule,
/// convRowsAvx512Bf16).
AFN_CPU_AVX512 void toBf16Emulated(std::uint16_t* d, const float* s, std::size_t n)
{
    for (std::size_t k = 0; k < n; k += 32) {
        const __m256i a = roundToBf16(_mm512_castps_si512(_mm512_loadu_ps(s + k)));
        const __m256i b = roundToBf16(_mm512_castps_si512(_mm512_loadu_ps(s + k + 16)));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + k), a);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + k + 16), b);
    }
}

/// Operands of one row pass over one group of NV output vectors (pairs: 32-bit units).
struct RowPass {
    const std::int32_t* band; ///< band row of output row y0, pixel -r
    long bandRow; ///< pairs per band row
    int c2; ///< pairs per band pixel
    const std::int32_t* w; ///< weights [tap][pair][cp16] + first output channel of the group
    const float* bias; ///< bias + first output channel of the group
    int pairs, k, cp16, nOut, width, pixStride;
    bool relu;
    float* dst; ///< output row y0 + first output channel of the group
    long dstRow;
};

template <int NV, int P>
AFN_CPU_AVX512_INLINE void storeBlock(const RowPass& r, __m512 (&acc)[P][NV], float* dst, int np)
{
    const __m512 zero = _mm512_set1_ps(0.0f);
    for (int p = 0; p < P; ++p) {
        if (p >= np)
            break;
        float* d = dst + static_cast<long>(p) * r.pixStride;
        for (int j = 0; j < NV; ++j) {
            const __m512 v
                = r.relu ? _mm512_mask_max_ps(acc[p][j], 0xFFFF, zero, acc[p][j]) : acc[p][j];
            const int n = r.nOut - 16 * j;
            if (n >= 16)
                _mm512_storeu_ps(d + 16 * j, v);
            else if (n > 0)
                _mm512_mask_storeu_ps(d + 16 * j, static_cast<__mmask16>((1u << n) - 1u), v);
        }
    }
}

/// P output pixels x NV x 16 output channels, VDPBF16PS. C2: the pairs per band pixel as a
/// compile-time constant (0: r.c2 at run time), so that pixel p's pair q is a constant
/// displacement from one register instead of an index register per pixel.
template <int NV, int P, int C2>
AFN_CPU_AVX512_BF16_INLINE void blockHardware(
    const RowPass& r, const std::int32_t* src, float* dst, int np)
{
    const int c2 = C2 ? C2 : r.c2;
    __m512 acc[P][NV];
    for (int j = 0; j < NV; ++j) {
        const __m512 b = _mm512_loadu_ps(r.bias + 16 * j);
        for (int p = 0; p < P; ++p)
            acc[p][j] = b;
    }
    const std::int32_t* wt = r.w;
    for (int ky = 0; ky < r.k; ++ky)
        for (int kx = 0; kx < r.k; ++kx) {
            const std::int32_t* s = src + ky * r.bandRow + kx * c2;
            for (int q = 0; q < r.pairs; ++q, wt += r.cp16) {
                __m512bh wv[NV];
                for (int j = 0; j < NV; ++j) {
                    const __m512i w = _mm512_loadu_si512(wt + 16 * j);
                    wv[j] = reinterpret_cast<const __m512bh&>(w);
                }
                for (int p = 0; p < P; ++p) {
                    std::int32_t pair;
                    std::memcpy(&pair, s + p * c2 + q, sizeof(pair));
                    const __m512i xi = _mm512_set1_epi32(pair);
                    const __m512bh x = reinterpret_cast<const __m512bh&>(xi);
                    for (int j = 0; j < NV; ++j)
                        acc[p][j] = _mm512_dpbf16_ps(acc[p][j], x, wv[j]);
                }
            }
        }
    storeBlock<NV, P>(r, acc, dst, np);
}

/// The same arithmetic with AVX-512F FMAs: channel 2q + 1 (high half) first, then 2q.
template <int NV, int P>
AFN_CPU_AVX512_INLINE void blockEmulated(
    const RowPass& r, const std::int32_t* src, float* dst, int np)
{
    const __m512i high = _mm512_set1_epi32(static_cast<int>(0xFFFF0000u));
    __m512 acc[P][NV];
    for (int j = 0; j < NV; ++j) {
        const __m512 b = _mm512_loadu_ps(r.bias + 16 * j);
        for (int p = 0; p < P; ++p)
            acc[p][j] = b;
    }
    const std::int32_t* wt = r.w;
    for (int ky = 0; ky < r.k; ++ky)
        for (int kx = 0; kx < r.k; ++kx) {
            const std::int32_t* s = src + ky * r.bandRow + kx * r.c2;
            for (int q = 0; q < r.pairs; ++q, wt += r.cp16) {
                __m512 wOdd[NV], wEven[NV];
                for (int j = 0; j < NV; ++j) {
                    const __m512i w = _mm512_loadu_si512(wt + 16 * j);
                    wOdd[j] = _mm512_castsi512_ps(_mm512_and_si512(w, high));
                    wEven[j] = _mm512_castsi512_ps(_mm512_slli_epi32(w, 16));
                }
                for (int p = 0; p < P; ++p) {
                    std::uint32_t v;
                    std::memcpy(&v, s + p * r.c2 + q, sizeof(v));
                    const __m512 xOdd
                        = _mm512_castsi512_ps(_mm512_set1_epi32(static_cast<int>(v & 0xFFFF0000u)));
                    const __m512 xEven
                        = _mm512_castsi512_ps(_mm512_set1_epi32(static_cast<int>(v << 16)));
                    for (int j = 0; j < NV; ++j) {
                        acc[p][j] = _mm512_fmadd_ps(xOdd, wOdd[j], acc[p][j]);
                        acc[p][j] = _mm512_fmadd_ps(xEven, wEven[j], acc[p][j]);
                    }
                }
            }
        }
    storeBlock<NV, P>(r, acc, dst, np);
}

template <int NV, int P, int C2> AFN_CPU_AVX512_BF16 void rowsHardware(const RowPass& r, int nRows)
{
    for (int i = 0; i < nRows; ++i) {
        const std::int32_t* src = r.band + i * r.bandRow;
        float* dst = r.dst + i * r.dstRow;
        int x = 0;
        for (; x + P <= r.width; x += P)
            blockHardware<NV, P, C2>(
                r, src + static_cast<long>(x) * r.c2, dst + static_cast<long>(x) * r.pixStride, P);
        if (x < r.width)
            blockHardware<NV, P, C2>(r, src + static_cast<long>(x) * r.c2,
                dst + static_cast<long>(x) * r.pixStride, r.width - x);
    }
}

/// rowsHardware with the band's pair stride as a constant for afn's band widths (16, 32, 48, 64
/// and 96 channels).
template <int NV, int P> void rowsHardwareFor(const RowPass& r, int nRows)
{
    switch (r.c2) {
    case 8:
        return rowsHardware<NV, P, 8>(r, nRows);
    case 16:
        return rowsHardware<NV, P, 16>(r, nRows);
    case 24:
        return rowsHardware<NV, P, 24>(r, nRows);
    case 32:
        return rowsHardware<NV, P, 32>(r, nRows);
    case 48:
        return rowsHardware<NV, P, 48>(r, nRows);
    default:
        return rowsHardware<NV, P, 0>(r, nRows);
    }
}

template <int NV, int P> AFN_CPU_AVX512 void rowsEmulated(const RowPass& r, int nRows)
{
    for (int i = 0; i < nRows; ++i) {
        const std::int32_t* src = r.band + i * r.bandRow;
        float* dst = r.dst + i * r.dstRow;
        int x = 0;
        for (; x + P <= r.width; x += P)
            blockEmulated<NV, P>(
                r, src + static_cast<long>(x) * r.c2, dst + static_cast<long>(x) * r.pixStride, P);
        if (x < r.width)
            blockEmulated<NV, P>(r, src + static_cast<long>(x) * r.c2,
                dst + static_cast<long>(x) * r.pixStride, r.width - x);
    }
}

// Pixels per block: as the fp32 kernels (24 accumulators; 14 for one vector).
template <int NV> constexpr int pixelsFor()
{
    return NV == 1 ? 14 : NV == 2 ? 12 : NV == 3 ? 8 : 6;
}

template <int NV> void rowsFor(const RowPass& r, int nRows, bool hardware)
{
    constexpr int P = pixelsFor<NV>();
    static_assert(P <= kConvBandSlackPixels);
    if (hardware)
        rowsHardwareFor<NV, P>(r, nRows);
    else
        rowsEmulated<NV, P>(r, nRows);
}

#endif // AFN_CPU_HAVE_AVX512

} // namespace

namespace {

void bandRowsBf16(const ConvArgs& a, int y0, int y1)
{
#ifdef AFN_CPU_HAVE_AVX512
    const int c = bandChannels(a.in);
    std::vector<float>& band = convBandBuffer();
    const Bf16Mode mode = activeBf16Mode();
    const bool hardware = mode != Bf16Mode::Emulated; // AMX implies AVX512_BF16 (cpu/isa.h)
    const int w = columnEnd(a) - a.x0;
    // Without AVX512_BF16 (or for bands too wide to compose) the fp32 band is filled and then
    // rounded to bf16 in place, front to back: value k's 2 bytes land at byte 2k,
    // below the floats not read yet (each step loads its floats before it stores), so no second
    // buffer is needed. This call's band is `used` values, whole steps of 32: the slack after it
    // (over 32 floats: c >= 16, 18 pixels) covers the rounding up. The bf16 slack after the
    // band is then zeroed (those bytes held floats already converted).
    const std::size_t slack = static_cast<std::size_t>(kConvBandSlackPixels + 2) * c;
    const std::size_t used
        = static_cast<std::size_t>(y1 - y0 + 2 * (a.k / 2)) * (w + 2 * (a.k / 2)) * c;
    const std::size_t n = (used + 31) / 32 * 32;
    // With AVX512_BF16 the band is written in bf16 directly (fillConvBandBf16Avx512,
    // cpu/conv_band_bf16.cpp); the buffer then needs half the floats of the fp32 band, and 16 more
    // for the alignment below.
    if (hardware && band.size() < (n + slack) / 2 + 16)
        band.resize((n + slack) / 2 + 16);
    // The bf16 band starts on a 64-byte boundary, 0-48 bytes into the buffer (malloc aligns to
    // 16): step k of the conversion loads floats k .. k + 31 (bytes 4 k .. 4 k + 127) before it
    // stores their 64 bytes at offset + 2 k, which stays below 4 k + 128, the next step's floats.
    // A tile row of 32 channels is then one cache line, not two.
    auto alignedBand16 = [&band] {
        const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(band.data());
        return reinterpret_cast<std::uint16_t*>(band.data())
            + ((64 - base % 64) % 64) / sizeof(std::uint16_t);
    };
    std::uint16_t* band16 = alignedBand16();
    if (!hardware || !fillConvBandBf16Avx512(a, y0, y1, c, band16, slack)) {
        fillConvBandAvx512(a, y0, y1, c, band);
        band16 = alignedBand16(); // the fill may have grown the buffer
        if (hardware)
            toBf16Hardware(band16, band.data(), n);
        else
            toBf16Emulated(band16, band.data(), n);
        std::memset(band16 + n, 0, sizeof(std::uint16_t) * slack);
    }
    if (a.wtbf16)
        return fewOutputsRowsBf16(a, band16, y0, y1, hardware);
    if (mode == Bf16Mode::Amx && a.wamx) {
        const AmxConvPass p { band16, static_cast<long>(w + 2 * (a.k / 2)) * c, c, a.wamx, a.bp16,
            a.k, a.cp16, a.outC, w, a.dstPix, a.relu, a.dst + (y0 - a.dstY0) * a.dstRow, a.dstRow };
        convRowsAmxBf16(p, y1 - y0);
        return;
    }
    const int pairs = (a.in + 1) / 2;
    const auto* band32 = reinterpret_cast<const std::int32_t*>(band16);
    const auto* w32 = reinterpret_cast<const std::int32_t*>(a.wbf16);
    for (int cb = 0; cb < a.cp16; cb += 64) {
        const int nv = std::min(4, (a.cp16 - cb) / 16);
        const RowPass r { band32, static_cast<long>(w + 2 * (a.k / 2)) * (c / 2), c / 2, w32 + cb,
            a.bp16 + cb, pairs, a.k, a.cp16, a.outC - cb, w, a.dstPix, a.relu,
            a.dst + (y0 - a.dstY0) * a.dstRow + cb, a.dstRow };
        switch (nv) {
        case 1:
            rowsFor<1>(r, y1 - y0, hardware);
            break;
        case 2:
            rowsFor<2>(r, y1 - y0, hardware);
            break;
        case 3:
            rowsFor<3>(r, y1 - y0, hardware);
            break;
        default:
            rowsFor<4>(r, y1 - y0, hardware);
            break;
        }
    }
#else
    (void)a, (void)y0, (void)y1;
#endif
}

} // namespace

void convRowsAvx512Bf16(const ConvArgs& a, int y0, int y1)
{
    const int group = bandRowGroup(a);
    for (int ya = y0; ya < y1; ya += group)
        bandRowsBf16(a, ya, std::min(y1, ya + group));
}

} // namespace afn::cpu
