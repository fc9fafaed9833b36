// SPDX-License-Identifier: Apache-2.0
// SVGF's per-row kernels (methods/svgf/denoiser.h for the method): 8 pixels of a row at a time on
// structure-of-arrays planes (methods/svgf/planes.h), compiled per instruction set (cpu/target.h)
// and chosen when the library loads. Every pixel runs the same code whatever the row split, so
// results are independent of the thread count.
//
// Accuracy against the former scalar code (libm expf per tap): the weights use cpu/simd.h's exp8
// (Cephes polynomial, about 2 ulp), FMA contraction on AVX2/AVX-512 machines, and denormals are
// flushed inside the kernels. Measured with afntool --denoise:method=svgf on examples/sequence
// frames 0-7 (320x180, float output) against the scalar build (main at 15a2fd3), AVX-512
// clone: max |difference| 7.2e-5 (on a value of 3.08, i.e. 2.3e-5 relative), PSNR >= 159.6 dB
// on every frame (peak = the scalar output's maximum).
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

/// One à-trous iteration (step 2^i) over rows [y0, y1).
struct AtrousArgs {
    const Planes* in = nullptr; ///< ColorPlane
    const Planes* invPhiL = nullptr; ///< 1 plane: 1 / (sigmaL * sqrt(g3x3(variance)) + 1e-10)
    const Guide* guide = nullptr;
    Planes* out = nullptr; ///< ColorPlane
    int step = 1;
    const WorkRegion* region = nullptr; ///< per row, the columns to compute (null: all)
};
void atrousRows(const AtrousArgs& a, int y0, int y1);

/// invPhiL of rows [y0, y1): 1 / (sigmaL * sqrt(max(0, g3x3(variance))) + 1e-10), g3x3 the 3x3
/// Gaussian (1/4 centre, 1/8 edges, 1/16 corners) over in-image taps, renormalised.
void invPhiRows(const Planes& in, float sigmaL, Planes& invPhiL, int y0, int y1);

/// Variance of rows [y0, y1): the temporal one where the history length reaches
/// `varianceHistory`, else the 7x7 cross-bilateral estimate (methods/svgf/denoiser.h).
struct VarianceArgs {
    const Planes* in = nullptr; ///< IntegratedPlane
    const Guide* guide = nullptr;
    Planes* out = nullptr; ///< ColorPlane
    float phiL = 4.0f; ///< luminance edge-stopping (sigmaL, not variance-scaled)
    float varianceHistory = 4.0f;
    const WorkRegion* region = nullptr; ///< per row, the columns to compute (null: all)
};

/// Columns [begin, end) of row y that a kernel computes: the region's span with its start rounded
/// down to a vector boundary (lanes are computed as without a region), or the whole row.
inline void regionColumns(const WorkRegion* region, int y, int width, int& begin, int& end)
{
    begin = region ? region->x0(y) / kLanes * kLanes : 0;
    end = region ? region->x1(y) : width;
}
void varianceRows(const VarianceArgs& a, int y0, int y1);

} // namespace afn::svgf
