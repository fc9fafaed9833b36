// SPDX-License-Identifier: Apache-2.0
// AVX-512 micro-kernels of nn::Conv (cpu/conv_kernel.h), used only where the CPU has AVX-512F
// (cpu/isa.h: chosen at run time; the functions carry their own target attribute, the build has
// no -march).
//
// Design (measured on a 2-core AMD EPYC with AVX-512, docs/performance.md):
// - Implicit GEMM without im2col: M = output pixels of a row, N = output channels, K = taps x
//   input channels. A task of rows first copies its input rows (plus the k/2-row halo) into a
//   zero-padded band: concat(U(up), same) per pixel, channels padded to a multiple of 16, one
//   zero pixel left and right. The micro-kernel then needs no border tests, no upsampling
//   arithmetic, and reads pixel p's channel c at a compile-time displacement p * C + c.
// - Register blocking: P output pixels x NV vectors of 16 output channels = 24 (NV 2..4) or 14
//   (NV 1) zmm accumulators; per input channel NV weight loads and P broadcast FMAs. Enough
//   independent accumulators to cover the FMA latency of two pipes; weights [tap][ci][co16] stream
//   from L1/L2, inputs are broadcast from the band (embedded broadcast operands).
// - Summation order per output: bias, then taps (ky, kx), then input channels (up, same), one FMA
//   each, the same order as the portable kernel, and independent of how rows are split among
//   threads: results are bit-identical for every thread count.
#include "cpu/conv_kernel.h"

#include "cpu/avx512.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace afn::cpu {

namespace {

constexpr int kMaxPixels = kConvBandSlackPixels; // largest P below: the band's zeroed slack

#ifdef AFN_CPU_HAVE_AVX512

/// `n` floats from s to d (masked 16-float loads and stores).
AFN_CPU_AVX512_INLINE void copyFloats(float* d, const float* s, int n)
{
    for (int k = 0; k < n; k += 16) {
        const __mmask16 m = firstLanes(n - k);
        _mm512_mask_storeu_ps(d + k, m, _mm512_maskz_loadu_ps(m, s + k));
    }
}

/// The band pixels of input columns [xa, xb) of one row (c floats each: U(up) pixel x/2, same
/// pixel x, zeros), with vector stores instead of three library calls per pixel.
AFN_CPU_AVX512 void fillPixels(
    float* d, int c, const float* up, int nu, const float* same, int ns, int xa, int xb)
{
    const __m512 zero = _mm512_set1_ps(0.0f);
    for (int x = xa; x < xb; ++x, d += c) {
        for (int k = 0; k < c; k += 16)
            _mm512_storeu_ps(d + k, zero);
        if (nu)
            copyFloats(d, up + static_cast<std::size_t>(x >> 1) * nu, nu);
        copyFloats(d + nu, same + static_cast<std::size_t>(x) * ns, ns);
    }
}

#endif // AFN_CPU_HAVE_AVX512

} // namespace

#ifdef AFN_CPU_HAVE_AVX512
void fillConvBandAvx512(const ConvArgs& a, int y0, int y1, int c, std::vector<float>& band)
{
    const auto [h, r, bw, xa, xb, lead, trail, rows] = convBandGeometry(a, y0, y1);
    const std::size_t rowFloats = static_cast<std::size_t>(bw) * c;
    const std::size_t slack = static_cast<std::size_t>(kMaxPixels + 2) * c;
    if (band.size() < rows * rowFloats + slack)
        band.resize(rows * rowFloats + slack);
    for (int i = 0; i < rows; ++i) {
        const int yy = y0 - r + i;
        float* row = band.data() + i * rowFloats;
        if (yy < 0 || yy >= h) {
            std::memset(row, 0, sizeof(float) * rowFloats);
            continue;
        }
        std::memset(row, 0, sizeof(float) * lead * c);
        std::memset(row + static_cast<std::size_t>(bw - trail) * c, 0, sizeof(float) * trail * c);
        float* d = row + static_cast<std::size_t>(lead) * c;
        if (a.nu == 0 && a.ns == c) {
            // The band pixel is the input pixel (no upsampled part, no channel padding): the
            // columns in one copy.
            std::memcpy(
                d, a.same->at(xa, yy), sizeof(float) * static_cast<std::size_t>(xb - xa) * c);
            continue;
        }
        fillPixels(
            d, c, a.nu ? a.up->at(0, yy >> 1) : nullptr, a.nu, a.same->at(0, yy), a.ns, xa, xb);
    }
    std::memset(band.data() + rows * rowFloats, 0, sizeof(float) * slack);
}
#endif

namespace {

#ifdef AFN_CPU_HAVE_AVX512

/// Operands of one row pass over one group of NV output vectors.
struct RowPass {
    const float* band; ///< band row of output row y0, pixel -r
    long bandRow; ///< floats per band row
    int c; ///< floats per band pixel (runtime stride when the template's C is 0)
    const float* w; ///< weights [tap][ci][cp16] + first output channel of the group
    const float* bias; ///< bias + first output channel of the group
    int in, k, cp16, nOut, width, pixStride;
    bool relu;
    float* dst; ///< output row y0 + first output channel of the group
    long dstRow;
};

/// P output pixels (np of them stored) x NV x 16 output channels.
template <int NV, int P, int C>
AFN_CPU_AVX512_INLINE void block(const RowPass& r, const float* src, float* dst, int np)
{
    const int cs = C ? C : r.c;
    __m512 acc[P][NV];
    for (int j = 0; j < NV; ++j) {
        const __m512 b = _mm512_loadu_ps(r.bias + 16 * j);
        for (int p = 0; p < P; ++p)
            acc[p][j] = b;
    }
    const float* wt = r.w;
    for (int ky = 0; ky < r.k; ++ky)
        for (int kx = 0; kx < r.k; ++kx) {
            const float* s = src + ky * r.bandRow + kx * cs;
            for (int ci = 0; ci < r.in; ++ci, wt += r.cp16) {
                __m512 wv[NV];
                for (int j = 0; j < NV; ++j)
                    wv[j] = _mm512_loadu_ps(wt + 16 * j);
                for (int p = 0; p < P; ++p) {
                    const __m512 x = _mm512_set1_ps(s[p * cs + ci]);
                    for (int j = 0; j < NV; ++j)
                        acc[p][j] = _mm512_fmadd_ps(x, wv[j], acc[p][j]);
                }
            }
        }
    const __m512 zero = _mm512_set1_ps(0.0f); // not setzero: GCC 12 -Wmaybe-uninitialized
    for (int p = 0; p < P; ++p) {
        if (p >= np)
            break;
        float* d = dst + static_cast<long>(p) * r.pixStride;
        for (int j = 0; j < NV; ++j) {
            // max(0, v) keeps NaN (as std::max(v, 0.0f) in the portable kernel).
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

template <int NV, int P, int C> AFN_CPU_AVX512 void rows(const RowPass& r, int nRows)
{
    const int cs = C ? C : r.c;
    for (int i = 0; i < nRows; ++i) {
        const float* src = r.band + i * r.bandRow;
        float* dst = r.dst + i * r.dstRow;
        int x = 0;
        for (; x + P <= r.width; x += P)
            block<NV, P, C>(
                r, src + static_cast<long>(x) * cs, dst + static_cast<long>(x) * r.pixStride, P);
        if (x < r.width)
            block<NV, P, C>(r, src + static_cast<long>(x) * cs,
                dst + static_cast<long>(x) * r.pixStride, r.width - x);
    }
}

// Pixels per block for NV vectors: 24 accumulators (14 for one vector: the broadcasts, one load
// per FMA there, bound it).
template <int NV> constexpr int pixelsFor()
{
    return NV == 1 ? 14 : NV == 2 ? 12 : NV == 3 ? 8 : 6;
}

template <int NV> void rowsForWidth(const RowPass& r, int nRows)
{
    constexpr int P = pixelsFor<NV>();
    switch (r.c) {
    case 16:
        return rows<NV, P, 16>(r, nRows);
    case 32:
        return rows<NV, P, 32>(r, nRows);
    case 48:
        return rows<NV, P, 48>(r, nRows);
    case 64:
        return rows<NV, P, 64>(r, nRows);
    case 96:
        return rows<NV, P, 96>(r, nRows);
    default:
        return rows<NV, P, 0>(r, nRows);
    }
}

/// P pixels from x (np of them stored) of rowsFewOutputs: P x NO independent accumulators (the
/// FMA latency is covered), each weight vector loaded once for the P pixels.
template <int NO, int P>
AFN_CPU_AVX512_INLINE void fewOutputsBlock(
    const ConvArgs& a, const float* src, long bandRow, int c, int x, int np, float* d)
{
    const int groups = c / 16, taps = a.k * a.k;
    __m512 acc[P][NO];
    for (int p = 0; p < P; ++p)
        for (int co = 0; co < NO; ++co)
            acc[p][co] = _mm512_set1_ps(0.0f);
    const float* wt = a.wt16;
    for (int t = 0; t < taps; ++t) {
        const float* s = src + (t / a.k) * bandRow + static_cast<long>(x + t % a.k) * c;
        for (int g = 0; g < groups; ++g) {
            __m512 wv[NO];
            for (int co = 0; co < NO; ++co)
                wv[co] = _mm512_loadu_ps(wt + static_cast<long>(co) * c + 16 * g);
            for (int p = 0; p < P; ++p) {
                const __m512 v = _mm512_loadu_ps(s + static_cast<long>(p) * c + 16 * g);
                for (int co = 0; co < NO; ++co)
                    acc[p][co] = _mm512_fmadd_ps(v, wv[co], acc[p][co]);
            }
        }
        wt += static_cast<long>(NO) * c;
    }
    for (int p = 0; p < P && p < np; ++p) {
        float* o = d + static_cast<long>(x + p) * a.dstPix;
        for (int co = 0; co < NO; ++co) {
            const float v = _mm512_reduce_add_ps(acc[p][co]) + a.bp16[co];
            o[co] = a.relu ? (v < 0.0f ? 0.0f : v) : v; // NaN kept, as the other kernels
        }
    }
}

/// Layers of NO <= kFewOutputs output channels (the AFN refinement's last layer, 16 -> 3): 16
/// input channels per vector instead of 16 output channels, so that no lane computes a padded
/// output. Blocks of P pixels, P x NO accumulators; per tap and group of 16 input channels NO
/// weight loads, then per pixel one load of the band pixel and NO FMAs; at the end each
/// accumulator's 16 lanes are summed (_mm512_reduce_add_ps), the bias added, ReLU applied.
/// Summation order: per lane the taps (ky, kx) and channel groups in order, then the lanes as a
/// fixed tree, then the bias: independent of the rows' split among threads and of the block
/// (bit-identical for every thread count), not the order of the portable kernel
/// (rounding-level differences, as the AFN engine's other AVX-512 stages). The last block's reads
/// past the row stay in the band's zeroed slack (kMaxPixels).
template <int NO>
AFN_CPU_AVX512 void rowsFewOutputs(
    const ConvArgs& a, const float* band, long bandRow, int c, int nRows, float* dst)
{
    constexpr int P = 24 / NO > 8 ? 8 : 24 / NO;
    static_assert(P <= kMaxPixels);
    const int w = columnEnd(a) - a.x0;
    for (int i = 0; i < nRows; ++i) {
        const float* src = band + i * bandRow;
        float* d = dst + i * a.dstRow;
        for (int x = 0; x < w; x += P)
            fewOutputsBlock<NO, P>(a, src, bandRow, c, x, w - x, d);
    }
}

#endif // AFN_CPU_HAVE_AVX512

} // namespace

std::vector<float>& convBandBuffer()
{
    thread_local std::vector<float> band;
    return band;
}

namespace {

void bandRowsFp32(const ConvArgs& a, int y0, int y1)
{
#ifdef AFN_CPU_HAVE_AVX512
    const int c = bandChannels(a.in);
    std::vector<float>& band = convBandBuffer();
    fillConvBandAvx512(a, y0, y1, c, band);
    const int w = columnEnd(a) - a.x0; // output columns
    if (a.wt16 && a.outC <= kFewOutputs) {
        const long bandRow = static_cast<long>(w + 2 * (a.k / 2)) * c;
        float* dst = a.dst + (y0 - a.dstY0) * a.dstRow;
        switch (a.outC) {
        case 1:
            return rowsFewOutputs<1>(a, band.data(), bandRow, c, y1 - y0, dst);
        case 2:
            return rowsFewOutputs<2>(a, band.data(), bandRow, c, y1 - y0, dst);
        case 3:
            return rowsFewOutputs<3>(a, band.data(), bandRow, c, y1 - y0, dst);
        default:
            return rowsFewOutputs<4>(a, band.data(), bandRow, c, y1 - y0, dst);
        }
    }
    for (int cb = 0; cb < a.cp16; cb += 64) {
        const int nv = std::min(4, (a.cp16 - cb) / 16);
        const RowPass r { band.data(), static_cast<long>(w + 2 * (a.k / 2)) * c, c, a.wp16 + cb,
            a.bp16 + cb, a.in, a.k, a.cp16, a.outC - cb, w, a.dstPix, a.relu,
            a.dst + (y0 - a.dstY0) * a.dstRow + cb, a.dstRow };
        switch (nv) {
        case 1:
            rowsForWidth<1>(r, y1 - y0);
            break;
        case 2:
            rowsForWidth<2>(r, y1 - y0);
            break;
        case 3:
            rowsForWidth<3>(r, y1 - y0);
            break;
        default:
            rowsForWidth<4>(r, y1 - y0);
            break;
        }
    }
#else
    (void)a, (void)y0, (void)y1;
#endif
}

} // namespace

void convRowsAvx512(const ConvArgs& a, int y0, int y1)
{
    if (a.wbf16 || a.wtbf16)
        return convRowsAvx512Bf16(a, y0, y1);
    const int group = bandRowGroup(a);
    for (int ya = y0; ya < y1; ya += group)
        bandRowsFp32(a, ya, std::min(y1, ya + group));
}

} // namespace afn::cpu
