// SPDX-License-Identifier: Apache-2.0
// The quarter-resolution scale's kernels and what follows it (quarter_pixel.h), one thread per
// pixel. Compiled with --fmad=false (cuda/CMakeLists.txt) like the CPU's float arithmetic.
#include "cuda/check.h"
#include "cuda/grid.cuh"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

__global__ void __launch_bounds__(kGridThreads) quarterDeltaKernel(QuarterArgs a)
{
    int x, y;
    if (gridItem(a.width, a.height, x, y))
        quarterDeltaPixel(a, x, y);
}

__global__ void __launch_bounds__(kGridThreads)
    addUpsampled4Kernel(const float* delta, float* fused, int width, int height)
{
    int x, y;
    if (gridItem(width, height, x, y))
        addUpsampled4Pixel(delta, fused, width, height, x, y);
}

__global__ void __launch_bounds__(kGridThreads)
    refineInputKernel(const float* fused, const std::uint16_t* x, std::uint16_t* r, long long n)
{
    const long long p = static_cast<long long>(blockIdx.x) * kGridThreads + threadIdx.x;
    if (p < n)
        refineInputPixel(fused, x, r, static_cast<std::size_t>(p));
}

__global__ void __launch_bounds__(kGridThreads)
    fusedOutputKernel(const float* fused, int paddedWidth, FinalOutput out)
{
    int x, y;
    if (gridItem(out.width, out.height, x, y))
        fusedOutputPixel(fused, paddedWidth, out, x, y);
}

} // namespace

void launchQuarterDelta(const QuarterArgs& a, cudaStream_t stream)
{
    quarterDeltaKernel<<<gridBlocks(static_cast<long long>(a.width) * a.height), kGridThreads, 0,
        stream>>>(a);
    AFN_CUDA_CHECK_LAUNCH("quarterDeltaKernel");
}

void launchAddUpsampled4(
    const float* delta, float* fused, int width, int height, cudaStream_t stream)
{
    addUpsampled4Kernel<<<gridBlocks(static_cast<long long>(width) * height), kGridThreads, 0,
        stream>>>(delta, fused, width, height);
    AFN_CUDA_CHECK_LAUNCH("addUpsampled4Kernel");
}

void launchRefineInput(const float* fused, const std::uint16_t* x, std::uint16_t* refineInput,
    int width, int height, cudaStream_t stream)
{
    const long long n = static_cast<long long>(width) * height;
    refineInputKernel<<<gridBlocks(n), kGridThreads, 0, stream>>>(fused, x, refineInput, n);
    AFN_CUDA_CHECK_LAUNCH("refineInputKernel");
}

void launchFusedOutput(
    const float* fused, int paddedWidth, const FinalOutput& out, cudaStream_t stream)
{
    fusedOutputKernel<<<gridBlocks(static_cast<long long>(out.width) * out.height), kGridThreads, 0,
        stream>>>(fused, paddedWidth, out);
    AFN_CUDA_CHECK_LAUNCH("fusedOutputKernel");
}

} // namespace afn::cuda
