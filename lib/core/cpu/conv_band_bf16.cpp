// SPDX-License-Identifier: Apache-2.0
// The bf16 convolutions' input band written in bf16 directly (cpu/conv_kernel.h,
// fillConvBandBf16Avx512), where the CPU has AVX512_BF16: each 16-channel chunk of a band pixel
// is composed in a register from masked loads of its U(up) and same channels and rounded by the
// hardware (VCVTNE2PS2BF16), two chunks to one 64-byte store. The values are those of the fp32
// band (fillConvBandAvx512) rounded one by one, without writing and reading the fp32 band.
#include "cpu/conv_kernel.h"

#include "cpu/avx512.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace afn::cpu {

#ifdef AFN_CPU_HAVE_AVX512

namespace {

/// Band pixels of at most this many 16-channel chunks are composed in registers
/// (fillConvBandBf16Avx512); wider ones (none in afn) take the fp32 band and its conversion.
constexpr int kMaxComposedChunks = 16;

/// Chunk k (band channels 16 k .. 16 k + 15) of one band pixel, composed from masked loads of its
/// U(up) channels and its same channels (lane l reads s[16 k + l - nu]; masked-off lanes, before s
/// or after its ns values, are not read), zero elsewhere: the fp32 band's value bits.
AFN_CPU_AVX512_BF16_INLINE __m512 bandChunk(
    const float* u, const float* s, int k, int nu, __mmask16 fromUp, __mmask16 fromSame)
{
    __m512 v = _mm512_set1_ps(0.0f);
    if (fromUp)
        v = _mm512_maskz_loadu_ps(fromUp, u + 16 * k);
    if (fromSame) {
        const std::intptr_t offset = static_cast<std::intptr_t>(16 * k) - nu;
        v = _mm512_mask_loadu_ps(v, fromSame,
            reinterpret_cast<const float*>(
                reinterpret_cast<std::uintptr_t>(s) + offset * sizeof(float)));
    }
    return v;
}

/// 16 floats rounded to bf16 (the hardware's rounding) and stored at o.
AFN_CPU_AVX512_BF16_INLINE void store16Bf16(std::uint16_t* o, __m512 v)
{
    const __m256bh b = _mm512_cvtneps_pbh(v);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(o), reinterpret_cast<const __m256i&>(b));
}

/// 32 floats (lo, then hi) rounded to bf16 and stored at o.
AFN_CPU_AVX512_BF16_INLINE void store32Bf16(std::uint16_t* o, __m512 lo, __m512 hi)
{
    const __m512bh b = _mm512_cvtne2ps_pbh(hi, lo);
    _mm512_storeu_si512(o, reinterpret_cast<const __m512i&>(b));
}

/// One band row's pixels: U(up) and same rows, their channels, the chunks' lane masks.
struct BandPixels {
    const float* up; ///< U(up)'s row (pixel x reads pixel x / 2), or null
    const float* same;
    int nu, ns;
    const __mmask16* fromUp;
    const __mmask16* fromSame;
};

/// Band pixels of input columns [xa, xb) in bf16 at o, Chunks 16-channel chunks each (0: the
/// runtime `chunks`).
template <int Chunks>
AFN_CPU_AVX512_BF16_INLINE void bandPixelsBf16(
    const BandPixels& b, int xa, int xb, std::uint16_t* o, int chunks = Chunks)
{
    const int nc = Chunks ? Chunks : chunks;
    __mmask16 mu[kMaxComposedChunks], ms[kMaxComposedChunks];
    for (int k = 0; k < nc; ++k)
        mu[k] = b.fromUp[k], ms[k] = b.fromSame[k];
    const int c = 16 * nc;
    for (int x = xa; x < xb; ++x, o += c) {
        const float* s = b.same + static_cast<std::size_t>(x) * b.ns;
        const float* u = b.up ? b.up + static_cast<std::size_t>(x >> 1) * b.nu : nullptr;
        int k = 0;
        for (; k + 2 <= nc; k += 2)
            store32Bf16(o + 16 * k, bandChunk(u, s, k, b.nu, mu[k], ms[k]),
                bandChunk(u, s, k + 1, b.nu, mu[k + 1], ms[k + 1]));
        if (k < nc)
            store16Bf16(o + 16 * k, bandChunk(u, s, k, b.nu, mu[k], ms[k]));
    }
}

} // namespace

AFN_CPU_AVX512_BF16 bool fillConvBandBf16Avx512(
    const ConvArgs& a, int y0, int y1, int c, std::uint16_t* d, std::size_t slack)
{
    const int chunks = c / 16;
    if (chunks > kMaxComposedChunks)
        return false;
    const auto [h, r, bw, xa, xb, lead, trail, rows] = convBandGeometry(a, y0, y1);
    const std::size_t rowValues = static_cast<std::size_t>(bw) * c;
    __mmask16 fromUp[kMaxComposedChunks], fromSame[kMaxComposedChunks];
    for (int k = 0; k < chunks; ++k) {
        unsigned u = 0, m = 0;
        for (int lane = 0; lane < 16; ++lane) {
            const int ch = 16 * k + lane;
            u |= static_cast<unsigned>(ch < a.nu) << lane;
            m |= static_cast<unsigned>(ch >= a.nu && ch - a.nu < a.ns) << lane;
        }
        fromUp[k] = static_cast<__mmask16>(u);
        fromSame[k] = static_cast<__mmask16>(m);
    }
    for (int i = 0; i < rows; ++i) {
        const int yy = y0 - r + i;
        std::uint16_t* row = d + i * rowValues;
        if (yy < 0 || yy >= h) {
            std::memset(row, 0, sizeof(std::uint16_t) * rowValues);
            continue;
        }
        std::memset(row, 0, sizeof(std::uint16_t) * lead * c);
        std::memset(
            row + static_cast<std::size_t>(bw - trail) * c, 0, sizeof(std::uint16_t) * trail * c);
        std::uint16_t* o = row + static_cast<std::size_t>(lead) * c;
        if (a.nu == 0 && a.ns == c) { // the band pixel is the input pixel: the row in one run
            const float* s = a.same->at(xa, yy);
            const std::size_t n = static_cast<std::size_t>(xb - xa) * c; // a multiple of 16
            std::size_t k = 0;
            for (; k + 32 <= n; k += 32)
                store32Bf16(o + k, _mm512_loadu_ps(s + k), _mm512_loadu_ps(s + k + 16));
            if (k < n)
                store16Bf16(o + k, _mm512_loadu_ps(s + k));
            continue;
        }
        const BandPixels px { a.nu ? a.up->at(0, yy >> 1) : nullptr, a.same->at(0, yy), a.nu, a.ns,
            fromUp, fromSame };
        switch (chunks) { // the chunk loop unrolled, its masks in registers, for afn's widths
        case 1:
            bandPixelsBf16<1>(px, xa, xb, o);
            break;
        case 2:
            bandPixelsBf16<2>(px, xa, xb, o);
            break;
        case 3:
            bandPixelsBf16<3>(px, xa, xb, o);
            break;
        case 4:
            bandPixelsBf16<4>(px, xa, xb, o);
            break;
        case 6:
            bandPixelsBf16<6>(px, xa, xb, o);
            break;
        default:
            bandPixelsBf16<0>(px, xa, xb, o, chunks);
            break;
        }
    }
    const std::size_t used = static_cast<std::size_t>(rows) * rowValues;
    const std::size_t n = (used + 31) / 32 * 32;
    std::memset(d + used, 0, sizeof(std::uint16_t) * (n - used + slack));
    return true;
}

#endif // AFN_CPU_HAVE_AVX512

} // namespace afn::cpu
