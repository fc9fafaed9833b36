// SPDX-License-Identifier: Apache-2.0
// SVGF's per-row kernels (methods/svgf/denoiser.h for the method): 8 pixels of a row at a time on
// structure-of-arrays planes (methods/svgf/planes.h), compiled per instruction set (cpu/target.h)
// and chosen when the library loads; the à-trous pass also 16 at a time with AVX-512, chosen at
// run time (cpu/isa.h). Every pixel runs the same code whatever the row split, so
// results are independent of the thread count.
//
// Accuracy against the former scalar code (libm expf per tap): the weights use cpu/simd.h's exp8
// (Cephes polynomial, about 2 ulp), FMA contraction on AVX2/AVX-512 machines, and denormals are
// flushed inside the kernels. Measured with afntool --denoise:method=svgf on examples/sequence
// frames 0-7 (320x180, float output) against the scalar build (main at 15a2fd3), AVX-512
// clone: max |difference| 7.2e-5 (on a value of 3.08, i.e. 2.3e-5 relative), PSNR >= 159.6 dB
// on every frame (peak = the scalar output's maximum). The AVX-512 à-trous kernel
// (atrous_avx512.cpp: base-2 exponential, shared depth denominators) against the portable one,
// same frames (main at 6625a64): max relative difference 1.1e-5, PSNR >= 160.9 dB; the portable
// path (AFN_CPU_ISA=portable) is bit-identical to 6625a64.
#pragma once

#include "filter/work_region.h"
#include "methods/svgf/guide.h"
#include "methods/svgf/planes.h"

namespace afn::svgf {

/// Planes of the filtered colour and variance buffers (the à-trous ping-pong).
enum ColorPlane { kRed, kGreen, kBlue, kVariance, kLuminance, kColorPlanes };
/// Planes of the temporally integrated colour and moments.
enum IntegratedPlane {
    kIntRed,
    kIntGreen,
    kIntBlue,
    kIntLuminance,
    kMoment1, ///< luminance
    kMoment2, ///< squared luminance
    kHistoryLength,
    kIntegratedPlanes
};

/// One à-trous iteration (step 2^i) over rows [y0, y1) (of rowOrder where given).
struct AtrousArgs {
    const Planes* in = nullptr; ///< ColorPlane
    /// The luminance term's scale: |l_p - l_q| * invPhiL(p), invPhiL = 1 / (sigmaL *
    /// sqrt(max(0, g3x3(variance))) + 1e-10), g3x3 the 3x3 Gaussian (1/4 centre, 1/8 edges, 1/16
    /// corners) of `in`'s variance over in-image taps, renormalised; computed per centre pixel.
    float sigmaL = 4.0f;
    const Guide* guide = nullptr;
    Planes* out = nullptr; ///< ColorPlane
    int step = 1;
    /// The rows in processing order: [y0, y1) indexes this list (nullptr: row y0 to y1 - 1).
    /// Denoiser::atrous orders rows by y mod step, so that consecutive rows share 4 of their 5
    /// tap rows and those stay in the cache at large steps.
    const int* rowOrder = nullptr;
    const WorkRegion* region = nullptr; ///< per row, the columns to compute (null: all)
    /// The column tile [x0, x1) to compute (multiples of 16 but the image's end): Denoiser::atrous
    /// runs a frame wider than kAtrousTile in tiles, so that the 5 tap rows of consecutive rows
    /// stay in the core's cache at 8K (the same pixels, the same bits).
    int x0 = 0, x1 = 1 << 30;
};
/// Widest column tile of an à-trous pass (a multiple of 16).
constexpr int kAtrousTile = 2048;
/// The kernel family of cpu::activeIsa(): atrousRowsAvx512 or atrousRowsPortable.
void atrousRows(const AtrousArgs& a, int y0, int y1);
/// 8 lanes, GCC vector extensions, cloned per instruction set (atrous_kernel.cpp).
void atrousRowsPortable(const AtrousArgs& a, int y0, int y1);
/// 16 lanes, AVX-512F (atrous_avx512.cpp); only where the CPU has it.
void atrousRowsAvx512(const AtrousArgs& a, int y0, int y1);

/// Variance of rows [y0, y1): the temporal one where the history length reaches
/// `varianceHistory`, else the 7x7 cross-bilateral estimate (methods/svgf/denoiser.h).
struct VarianceArgs {
    const Planes* in = nullptr; ///< IntegratedPlane
    const Guide* guide = nullptr;
    Planes* out = nullptr; ///< ColorPlane
    float phiL = 4.0f; ///< luminance edge-stopping (sigmaL, not variance-scaled)
    float varianceHistory = 4.0f;
    /// Spread sparse samples (Settings::spread): the luminance term of each short-history
    /// pixel's estimate is scaled by 1 - sparseShare(cv) of its neighbourhood (below).
    bool spread = false;
    const WorkRegion* region = nullptr; ///< per row, the columns to compute (null: all)
};

/// The share of the 7x7 estimate's luminance edge-stopping that `spread` drops, from the
/// coefficient of variation cv = sd / mean of the neighbourhood's luminance (the moments' 7x7
/// estimate with the normal and depth weights only): 0 up to kSparseCvLow, 1 from kSparseCvHigh,
/// linear between. A neighbourhood of a few bright samples among dark ones (1 spp, dark scenes,
/// the frame after a cut) has a cv of 2-5, and the paper's luminance weights keep each bright
/// sample to itself and each dark pixel dark (methods/svgf/denoiser.h). Gradients, textures of
/// the light and the lit side of an edge stay below 1; the dark side of a high-contrast edge
/// reaches it within 3 pixels (a 10:1 edge: cv 1.4 where one column in seven is lit), where
/// some of the light spreads over the edge on these first frames.
constexpr float kSparseCvLow = 1.0f, kSparseCvHigh = 3.0f;
inline float sparseShare(float cv)
{
    const float r = (cv - kSparseCvLow) * (1.0f / (kSparseCvHigh - kSparseCvLow));
    return r > 0.0f ? (r < 1.0f ? r : 1.0f) : 0.0f; // NaN -> 0
}

/// Columns [begin, end) of row y that a kernel computes: the region's span with its start rounded
/// down to a boundary of `lanes` (vectors start where they do without a region), or the whole
/// row; begin >= end for a row the region leaves out.
inline void regionColumns(
    const WorkRegion* region, int y, int width, int& begin, int& end, int lanes = kLanes)
{
    begin = region ? region->x0(y) / lanes * lanes : 0;
    end = region ? region->x1(y) : width;
}
/// The kernel family of cpu::activeIsa(): varianceRowsAvx512 or varianceRowsPortable.
void varianceRows(const VarianceArgs& a, int y0, int y1);
/// 8 lanes, GCC vector extensions, cloned per instruction set (variance_kernel.cpp).
void varianceRowsPortable(const VarianceArgs& a, int y0, int y1);
/// 16 lanes, AVX-512F (variance_avx512.cpp); only where the CPU has it.
void varianceRowsAvx512(const VarianceArgs& a, int y0, int y1);

} // namespace afn::svgf
