// SPDX-License-Identifier: Apache-2.0
// AFN large's kernels besides the convolutions (large_pixel.h): one thread per 2 x 2 block of the
// padded frame for the input preparation and the scale fusion, one per pixel otherwise.
// Compiled with --fmad=false (cuda/CMakeLists.txt) like the CPU's float arithmetic.
#include "cuda/check.h"
#include "cuda/grid.cuh"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

__global__ void __launch_bounds__(kGridThreads) largePrepareKernel(LargePrepareBuffers b)
{
    int xh, yh;
    if (!gridItem(b.paddedWidth / 2, b.paddedHeight / 2, xh, yh))
        return;
    const DepthScale ds = b.depth ? depthScale(b.depthRange[0], b.depthRange[1]) : DepthScale {};
    largePrepareBlock(b, ds, xh, yh);
}

__global__ void __launch_bounds__(kGridThreads)
    down2Kernel(const float* in, float* out, int w, int h, int channels)
{
    int x, y;
    if (gridItem(w, h, x, y))
        down2Pixel(in, out, w, channels, x, y);
}

__global__ void __launch_bounds__(kGridThreads) largeFilterKernel(LargeFilterArgs a)
{
    int x, y;
    if (gridItem(a.width, a.height, x, y))
        largeFilterPixel(a, x, y);
}

__global__ void __launch_bounds__(kGridThreads) fuseScalesKernel(
    float* fine, const float* coarse, const float* logits, int stride, int channel, int w, int h)
{
    int cx, cy;
    if (gridItem(w / 2, h / 2, cx, cy))
        fuseScalesBlock(fine, coarse, logits, stride, channel, w, cx, cy);
}

__global__ void __launch_bounds__(kGridThreads)
    largeRefineInputKernel(const float* o, const std::uint16_t* x, std::uint16_t* r, long long n)
{
    const long long p = static_cast<long long>(blockIdx.x) * kGridThreads + threadIdx.x;
    if (p < n)
        largeRefineInputPixel(o, x, r, static_cast<std::size_t>(p));
}

} // namespace

void launchLargePrepare(const LargePrepareBuffers& b, cudaStream_t stream)
{
    const long long blocks = static_cast<long long>(b.paddedWidth / 2) * (b.paddedHeight / 2);
    largePrepareKernel<<<gridBlocks(blocks), kGridThreads, 0, stream>>>(b);
    AFN_CUDA_CHECK_LAUNCH("largePrepareKernel");
}

void launchDown2(const float* in, float* out, int w, int h, int channels, cudaStream_t stream)
{
    down2Kernel<<<gridBlocks(static_cast<long long>(w) * h), kGridThreads, 0, stream>>>(
        in, out, w, h, channels);
    AFN_CUDA_CHECK_LAUNCH("down2Kernel");
}

void launchLargeFilter(const LargeFilterArgs& a, cudaStream_t stream)
{
    largeFilterKernel<<<gridBlocks(static_cast<long long>(a.width) * a.height), kGridThreads, 0,
        stream>>>(a);
    AFN_CUDA_CHECK_LAUNCH("largeFilterKernel");
}

void launchFuseScales(float* fine, const float* coarse, const float* logits, int logitStride,
    int channel, int width, int height, cudaStream_t stream)
{
    fuseScalesKernel<<<gridBlocks(static_cast<long long>(width / 2) * (height / 2)), kGridThreads,
        0, stream>>>(fine, coarse, logits, logitStride, channel, width, height);
    AFN_CUDA_CHECK_LAUNCH("fuseScalesKernel");
}

void launchLargeRefineInput(const float* o, const std::uint16_t* x, std::uint16_t* refineInput,
    int width, int height, cudaStream_t stream)
{
    const long long n = static_cast<long long>(width) * height;
    largeRefineInputKernel<<<gridBlocks(n), kGridThreads, 0, stream>>>(o, x, refineInput, n);
    AFN_CUDA_CHECK_LAUNCH("largeRefineInputKernel");
}

} // namespace afn::cuda
