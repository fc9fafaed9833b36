// SPDX-License-Identifier: Apache-2.0
// The highlight bypass of afn (stages/highlight_bypass.h) for the CUDA engine, operation for
// operation as the CPU's: the histogram of the accumulated colour's largest channel over every
// kHighlightStride-th row and column (integer counts, so the order of the atomic additions does
// not matter), the limit from it (one thread), the network's colour inputs clamped at the limit
// and the excess added back to the output, times the remodulation's albedo factor. Compiled with
// --fmad=false (highlight.cu), as the CPU code is compiled without contraction: the CPU's bits.
#pragma once

#include "cuda/device_math.h"

namespace afn::cuda {

constexpr int kHighlightStride = 4;
constexpr int kHighlightLowest = -64, kHighlightHighest = 64;
constexpr int kHighlightBins = kHighlightHighest - kHighlightLowest + 1;

/// Samples of the histogram along a side of `size` pixels.
AFN_HD int highlightSamples(int size)
{
    return (size + kHighlightStride - 1) / kHighlightStride;
}

/// The histogram bin of v (highlight_bypass.cpp binOf): e - kHighlightLowest for v in
/// [2^(e-1), 2^e), clamped; 0 for v <= 0. From the exponent bits: std::frexp's e for normal
/// floats; subnormals fall in bin 0 either way.
AFN_HD int highlightBin(float v)
{
    if (!(v > 0.0f))
        return 0;
    const int e = static_cast<int>((floatBits(v) >> 23) & 0xffu) - 126;
    return (e < kHighlightLowest           ? kHighlightLowest
                   : e > kHighlightHighest ? kHighlightHighest
                                           : e)
        - kHighlightLowest;
}

/// The largest channel of a pixel (std::max({ r, g, b })).
AFN_HD float highlightLargest(const float* p)
{
    float m = p[0];
    if (m < p[1])
        m = p[1];
    if (m < p[2])
        m = p[2];
    return m;
}

/// The limit from the histogram of n samples (highlightLimit): factor times the upper edge of
/// the first bin whose cumulative count reaches ceil(0.99 n); +infinity when factor <= 0.
AFN_HD float highlightLimitFromCounts(const unsigned* counts, long long n, float factor)
{
    if (!(factor > 0.0f) || n <= 0)
        return bitsFloat(0x7f800000u);
    const long long target = static_cast<long long>(ceil(0.99 * static_cast<double>(n)));
    long long below = 0;
    int bin = 0;
    for (; bin < kHighlightBins - 1; ++bin) {
        below += counts[bin];
        if (below >= target)
            break;
    }
    const int e = bin + kHighlightLowest; // 2^e, a normal float for e in [-64, 64]
    return factor * bitsFloat(static_cast<std::uint32_t>(e + 127) << 23);
}

/// A colour value clamped at the limit (std::min(v, limit)).
AFN_HD float clampHighlight(float v, float limit)
{
    return limit < v ? limit : v;
}

/// Add the excess of accumulated pixel `ta` (3 floats) over the limit to output pixel `out`, each
/// channel times the remodulation's factor of `albedo` (null: 1); nothing where no channel
/// exceeds the limit (HighlightBypass::split and addExcess).
AFN_HD void addHighlightExcess(
    const float* ta, const float* albedo, bool plainAlbedo, float limit, float* out)
{
    if (!(ta[0] > limit || ta[1] > limit || ta[2] > limit))
        return;
    for (int k = 0; k < 3; ++k) {
        const float d = ta[k] - limit;
        const float e = d > 0.0f ? d : 0.0f; // std::max(d, 0.0f)
        out[k] += e * (albedo ? albedoFactor(albedo[k], plainAlbedo) : 1.0f);
    }
}

} // namespace afn::cuda
