// SPDX-License-Identifier: Apache-2.0
// AFN large's kernels besides the convolutions (large_pixel.h): one thread per 2 x 2 block of the
// padded frame for the input preparation and the scale fusion, one per pixel otherwise.
// Compiled with --fmad=false (cuda/CMakeLists.txt) like the CPU's float arithmetic.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kThreads = 256;

unsigned blocksFor(long long items)
{
    return static_cast<unsigned>((items + kThreads - 1) / kThreads);
}

__device__ bool gridIndex(int width, int height, int& x, int& y)
{
    const long long i = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (i >= static_cast<long long>(width) * height)
        return false;
    x = static_cast<int>(i % width);
    y = static_cast<int>(i / width);
    return true;
}

__global__ void __launch_bounds__(kThreads) largePrepareKernel(LargePrepareBuffers b)
{
    int xh, yh;
    if (!gridIndex(b.paddedWidth / 2, b.paddedHeight / 2, xh, yh))
        return;
    const DepthScale ds = b.depth ? depthScale(b.depthRange[0], b.depthRange[1]) : DepthScale {};
    largePrepareBlock(b, ds, xh, yh);
}

__global__ void __launch_bounds__(kThreads)
    down2Kernel(const float* in, float* out, int w, int h, int channels)
{
    int x, y;
    if (gridIndex(w, h, x, y))
        down2Pixel(in, out, w, channels, x, y);
}

__global__ void __launch_bounds__(kThreads) largeFilterKernel(LargeFilterArgs a)
{
    int x, y;
    if (gridIndex(a.width, a.height, x, y))
        largeFilterPixel(a, x, y);
}

__global__ void __launch_bounds__(kThreads) fuseScalesKernel(
    float* fine, const float* coarse, const float* logits, int stride, int channel, int w, int h)
{
    int cx, cy;
    if (gridIndex(w / 2, h / 2, cx, cy))
        fuseScalesBlock(fine, coarse, logits, stride, channel, w, cx, cy);
}

__global__ void __launch_bounds__(kThreads)
    largeRefineInputKernel(const float* o, const std::uint16_t* x, std::uint16_t* r, long long n)
{
    const long long p = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (p < n)
        largeRefineInputPixel(o, x, r, static_cast<std::size_t>(p));
}

} // namespace

void launchLargePrepare(const LargePrepareBuffers& b, cudaStream_t stream)
{
    const long long blocks = static_cast<long long>(b.paddedWidth / 2) * (b.paddedHeight / 2);
    largePrepareKernel<<<blocksFor(blocks), kThreads, 0, stream>>>(b);
    AFN_CUDA_CHECK_LAUNCH("largePrepareKernel");
}

void launchDown2(const float* in, float* out, int w, int h, int channels, cudaStream_t stream)
{
    down2Kernel<<<blocksFor(static_cast<long long>(w) * h), kThreads, 0, stream>>>(
        in, out, w, h, channels);
    AFN_CUDA_CHECK_LAUNCH("down2Kernel");
}

void launchLargeFilter(const LargeFilterArgs& a, cudaStream_t stream)
{
    largeFilterKernel<<<blocksFor(static_cast<long long>(a.width) * a.height), kThreads, 0,
        stream>>>(a);
    AFN_CUDA_CHECK_LAUNCH("largeFilterKernel");
}

void launchFuseScales(float* fine, const float* coarse, const float* logits, int logitStride,
    int channel, int width, int height, cudaStream_t stream)
{
    fuseScalesKernel<<<blocksFor(static_cast<long long>(width / 2) * (height / 2)), kThreads, 0,
        stream>>>(fine, coarse, logits, logitStride, channel, width, height);
    AFN_CUDA_CHECK_LAUNCH("fuseScalesKernel");
}

void launchLargeRefineInput(const float* o, const std::uint16_t* x, std::uint16_t* refineInput,
    int width, int height, cudaStream_t stream)
{
    const long long n = static_cast<long long>(width) * height;
    largeRefineInputKernel<<<blocksFor(n), kThreads, 0, stream>>>(o, x, refineInput, n);
    AFN_CUDA_CHECK_LAUNCH("largeRefineInputKernel");
}

} // namespace afn::cuda
