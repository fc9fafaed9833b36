// SPDX-License-Identifier: Apache-2.0
// Layers of at most kFewOutputs output channels in bfloat16 (cpu/conv_kernel.h,
// ConvArgs::wtbf16): the AFN refinement's last layer (16 -> 3) and the albedo trust's head.
//
// The fp32 kernel of these layers (cpu/conv_avx512.cpp, rowsFewOutputs) puts 16 input channels in
// the lanes and sums each accumulator's lanes at the end; the sums, not the multiply-adds, were
// most of its time. Here one output channel of 16 pixels is computed at a time:
// - Per kernel row ky, output pixel x reads the band's k pixels x .. x + k - 1 of that row: k x c
//   contiguous bf16 values (c = the band's channels). The weights of (ky, co) are stored in that
//   order, [kx][ci padded to c], padded with zeros to whole vectors of 32, so each kernel row is
//   ceil(k c / 32) VDPBF16PS of a band load against a weight vector held in a register (3 x 2 for
//   3x3 over 16 channels, against 9 x 3 FMAs per pixel in fp32). k c is a multiple of 16: a last
//   half vector is a 256-bit load, zero-extended.
// - The 16 pixels' accumulators are summed lane-wise by one transpose-and-add tree (45
//   instructions for 16 sums instead of 16 reductions of 8), which yields the 16 sums in one
//   vector: bias added, ReLU, then scattered to the pixels' channel co.
// - The loops run kernel rows and vectors outside and the 16 pixels inside, so 16 independent
//   accumulators hide the instruction's latency. A row's last block computes all 16 pixels and
//   stores its np: the others read the next band row or, on the last band row, at most 15 pixels
//   into the band's slack (kConvBandSlackPixels + 2 pixels).
// channelHardware and channelEmulated differ in the multiply-add only: the first needs the
// AVX512_BF16 target, which the emulation (for CPUs without it) must not be compiled for.
// Summation order, fixed and independent of rows, columns and threads: per lane the kernel rows,
// then the row's vectors in order, within a pair channel 2q + 1 then 2q (the instruction's order);
// then the lanes by the tree; then the bias. Without AVX512_BF16 the same arithmetic runs with
// AVX-512F FMAs on the halves widened to fp32: the same bits (denormals aside, as
// cpu/conv_avx512_bf16.cpp).
#include "cpu/conv_kernel.h"

#include "cpu/avx512.h"

#include <algorithm>
#include <cstdint>

namespace afn::cpu {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// Most weight vectors of one output channel held in registers (k x chunks): 3x3 over 32
/// channels. Wider layers load theirs from memory (none in afn).
constexpr int kMaxHeldVectors = 9;

/// Lane p of the result: the sum of the 16 lanes of acc[p]. Tree: 128-bit blocks, then 128-bit
/// blocks again, then lane pairs twice; the inputs are taken in the order that leaves pixel p in
/// lane p (slot s holds acc[(s % 4) * 4 + s / 4]).
AFN_CPU_AVX512_INLINE __m512 sumLanes16(const __m512 (&acc)[16])
{
    __m512 s1[8];
    for (int i = 0; i < 8; ++i) {
        const __m512 a = acc[((2 * i) % 4) * 4 + (2 * i) / 4];
        const __m512 b = acc[((2 * i + 1) % 4) * 4 + (2 * i + 1) / 4];
        s1[i] = _mm512_add_ps(_mm512_shuffle_f32x4(a, b, 0x44), _mm512_shuffle_f32x4(a, b, 0xEE));
    }
    __m512 s2[4];
    for (int j = 0; j < 4; ++j) {
        const __m512 a = s1[2 * j], b = s1[2 * j + 1];
        s2[j] = _mm512_add_ps(_mm512_shuffle_f32x4(a, b, 0x88), _mm512_shuffle_f32x4(a, b, 0xDD));
    }
    __m512 s3[2];
    for (int m = 0; m < 2; ++m) {
        const __m512 a = s2[2 * m], b = s2[2 * m + 1];
        s3[m] = _mm512_add_ps(_mm512_unpacklo_ps(a, b), _mm512_unpackhi_ps(a, b));
    }
    return _mm512_add_ps(
        _mm512_shuffle_ps(s3[0], s3[1], 0x44), _mm512_shuffle_ps(s3[0], s3[1], 0xEE));
}

/// One layer's operands (values: bf16 elements).
struct FewPass {
    const std::uint16_t* band; ///< band row of output row y0, pixel -r
    long bandRow; ///< values per band row
    int c; ///< values per band pixel
    const std::uint16_t* w; ///< [ky][co][chunks x 32]
    const float* bias;
    int k, chunks, outC, width, dstPix;
    bool relu;
    float* dst; ///< output row y0, column 0
    long dstRow;
};

/// Chunk j of one kernel row: 32 values, or 16 zero-extended where the run ends (k c is a multiple
/// of 16).
AFN_CPU_AVX512_INLINE __m512i loadChunk(const std::uint16_t* s, int j, int runValues)
{
    if (32 * j + 16 < runValues)
        return _mm512_loadu_si512(s + 32 * j);
    return _mm512_zextsi256_si512(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + 32 * j)));
}

/// Values from one kernel row's weights to the next: [ky][co][chunks x 32].
AFN_CPU_AVX512_INLINE long weightRow(const FewPass& f)
{
    return static_cast<long>(f.outC) * f.chunks * 32;
}

/// The weight vectors of output channel co (all kernel rows) into wv (K, Chunks: compile-time
/// shape; 0: the pass's, read from memory by the kernel instead).
template <int K, int Chunks>
AFN_CPU_AVX512_INLINE const std::uint16_t* loadWeights(const FewPass& f, int co, __m512i* wv)
{
    const std::uint16_t* w = f.w + static_cast<long>(co) * f.chunks * 32;
    if constexpr (K && Chunks)
        for (int ky = 0; ky < K; ++ky)
            for (int j = 0; j < Chunks; ++j)
                wv[ky * Chunks + j] = _mm512_loadu_si512(w + ky * weightRow(f) + 32 * j);
    return w;
}

/// Weight vector (ky, j): held in wv, or loaded from w for the run-time shape.
template <int K, int Chunks>
AFN_CPU_AVX512_INLINE __m512i weight(
    const FewPass& f, const __m512i* wv, const std::uint16_t* w, int ky, int j)
{
    if constexpr (K && Chunks)
        return wv[ky * Chunks + j];
    else
        return _mm512_loadu_si512(w + ky * weightRow(f) + 32 * j);
}

/// The 16 pixels' sums plus the bias, ReLU, stored to channel co of pixels x .. x + np - 1.
AFN_CPU_AVX512_INLINE void storeChannel(
    const FewPass& f, const __m512 (&acc)[16], float* d, int x, int np, int co)
{
    __m512 v = _mm512_add_ps(sumLanes16(acc), _mm512_set1_ps(f.bias[co]));
    if (f.relu)
        v = _mm512_max_ps(_mm512_setzero_ps(), v); // NaN kept (MAXPS returns the second operand)
    const __m512i index = _mm512_mullo_epi32(
        _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
        _mm512_set1_epi32(f.dstPix));
    const __mmask16 m = np >= 16 ? static_cast<__mmask16>(0xFFFF) : firstLanes(np);
    _mm512_mask_i32scatter_ps(d + static_cast<long>(x) * f.dstPix + co, m, index, v, 4);
}

template <int K, int Chunks> constexpr int heldVectors()
{
    static_assert(K * Chunks <= kMaxHeldVectors);
    return K && Chunks ? K * Chunks : 1;
}

/// Output channel co of pixels x .. x + np - 1 of one row with VDPBF16PS.
template <int K, int Chunks>
AFN_CPU_AVX512_BF16_INLINE void channelHardware(
    const FewPass& f, const std::uint16_t* src, float* d, int x, int np, int co)
{
    const int k = K ? K : f.k, chunks = Chunks ? Chunks : f.chunks, run = k * f.c;
    __m512i wv[heldVectors<K, Chunks>()];
    const std::uint16_t* w = loadWeights<K, Chunks>(f, co, wv);
    __m512 acc[16];
    for (int p = 0; p < 16; ++p)
        acc[p] = _mm512_setzero_ps();
    const std::uint16_t* s = src + static_cast<long>(x) * f.c;
    for (int ky = 0; ky < k; ++ky, s += f.bandRow)
        for (int j = 0; j < chunks; ++j) {
            const __m512i wj = weight<K, Chunks>(f, wv, w, ky, j);
            const __m512bh wb = reinterpret_cast<const __m512bh&>(wj);
            for (int p = 0; p < 16; ++p) {
                const __m512i xv = loadChunk(s + p * f.c, j, run);
                acc[p] = _mm512_dpbf16_ps(acc[p], reinterpret_cast<const __m512bh&>(xv), wb);
            }
        }
    storeChannel(f, acc, d, x, np, co);
}

/// The same with AVX-512F: per lane channel 2q + 1's product, then 2q's (the instruction's order).
template <int K, int Chunks>
AFN_CPU_AVX512_INLINE void channelEmulated(
    const FewPass& f, const std::uint16_t* src, float* d, int x, int np, int co)
{
    const int k = K ? K : f.k, chunks = Chunks ? Chunks : f.chunks, run = k * f.c;
    const __m512i high = _mm512_set1_epi32(static_cast<int>(0xFFFF0000u));
    __m512i wv[heldVectors<K, Chunks>()];
    const std::uint16_t* w = loadWeights<K, Chunks>(f, co, wv);
    __m512 acc[16];
    for (int p = 0; p < 16; ++p)
        acc[p] = _mm512_setzero_ps();
    const std::uint16_t* s = src + static_cast<long>(x) * f.c;
    for (int ky = 0; ky < k; ++ky, s += f.bandRow)
        for (int j = 0; j < chunks; ++j) {
            const __m512i wj = weight<K, Chunks>(f, wv, w, ky, j);
            const __m512 wOdd = _mm512_castsi512_ps(_mm512_and_si512(wj, high));
            const __m512 wEven = _mm512_castsi512_ps(_mm512_slli_epi32(wj, 16));
            for (int p = 0; p < 16; ++p) {
                const __m512i xv = loadChunk(s + p * f.c, j, run);
                acc[p] = _mm512_fmadd_ps(
                    _mm512_castsi512_ps(_mm512_and_si512(xv, high)), wOdd, acc[p]);
                acc[p] = _mm512_fmadd_ps(
                    _mm512_castsi512_ps(_mm512_slli_epi32(xv, 16)), wEven, acc[p]);
            }
        }
    storeChannel(f, acc, d, x, np, co);
}

template <int K, int Chunks> AFN_CPU_AVX512_BF16 void rowsHardware(const FewPass& f, int nRows)
{
    for (int i = 0; i < nRows; ++i)
        for (int x = 0; x < f.width; x += 16)
            for (int co = 0; co < f.outC; ++co)
                channelHardware<K, Chunks>(f, f.band + i * f.bandRow, f.dst + i * f.dstRow, x,
                    std::min(16, f.width - x), co);
}

template <int K, int Chunks> AFN_CPU_AVX512 void rowsEmulated(const FewPass& f, int nRows)
{
    for (int i = 0; i < nRows; ++i)
        for (int x = 0; x < f.width; x += 16)
            for (int co = 0; co < f.outC; ++co)
                channelEmulated<K, Chunks>(f, f.band + i * f.bandRow, f.dst + i * f.dstRow, x,
                    std::min(16, f.width - x), co);
}

template <int K, int Chunks> void rowsShape(const FewPass& f, int nRows, bool hardware)
{
    if (hardware)
        rowsHardware<K, Chunks>(f, nRows);
    else
        rowsEmulated<K, Chunks>(f, nRows);
}

} // namespace

void fewOutputsRowsBf16(const ConvArgs& a, const std::uint16_t* band, int y0, int y1, bool hardware)
{
    const int c = bandChannels(a.in), w = columnEnd(a) - a.x0;
    const FewPass f { band, static_cast<long>(w + 2 * (a.k / 2)) * c, c, a.wtbf16, a.bp16, a.k,
        fewOutputsChunks(a.k, a.in), a.outC, w, a.dstPix, a.relu, a.dst + (y0 - a.dstY0) * a.dstRow,
        a.dstRow };
    const int n = y1 - y0;
    if (f.k == 3 && f.chunks == 2)
        return rowsShape<3, 2>(f, n, hardware);
    if (f.k == 3 && f.chunks == 3)
        return rowsShape<3, 3>(f, n, hardware);
    if (f.k == 1 && f.chunks == 1)
        return rowsShape<1, 1>(f, n, hardware);
    rowsShape<0, 0>(f, n, hardware);
}

#else

void fewOutputsRowsBf16(const ConvArgs&, const std::uint16_t*, int, int, bool) { }

#endif // AFN_CPU_HAVE_AVX512

} // namespace afn::cpu
