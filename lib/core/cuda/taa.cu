// SPDX-License-Identifier: Apache-2.0
// afn's output TAA (taa_pixel.h), one thread per pixel. Compiled with --fmad=false
// (cuda/CMakeLists.txt), as stages/taa.cpp is compiled without contraction: the CPU's bits.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kBlockX = 16, kBlockY = 16;

__global__ void __launch_bounds__(kBlockX* kBlockY)
    taaKernel(TaaBuffers a, TemporalBuffers t, TrustBuffers trust, const FrameConstants* frame)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    if (x >= a.width || y >= a.height)
        return;
    const FrameConstants& f = *frame;
    taaPixel(a, t, f, trustMeasured(f.hasHistory, f.antilag) ? &trust : nullptr, x, y);
}

} // namespace

void launchTaa(const TaaBuffers& a, const TemporalBuffers& t, const TrustBuffers& trust,
    const FrameConstants* frame, cudaStream_t stream)
{
    const dim3 block(kBlockX, kBlockY);
    const dim3 grid((a.width + kBlockX - 1) / kBlockX, (a.height + kBlockY - 1) / kBlockY);
    taaKernel<<<grid, block, 0, stream>>>(a, t, trust, frame);
    AFN_CUDA_CHECK_LAUNCH("taaKernel");
}

} // namespace afn::cuda
