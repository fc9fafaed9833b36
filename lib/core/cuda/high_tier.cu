// SPDX-License-Identifier: Apache-2.0
// The quality tier high's mirroring, sum and mean (high_tier_pixel.h), one thread per pixel.
// Compiled with --fmad=false (cuda/CMakeLists.txt): the mean's remodulation as the CPU's.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kBlockX = 16, kBlockY = 16;

dim3 gridFor(int w, int h)
{
    return dim3((w + kBlockX - 1) / kBlockX, (h + kBlockY - 1) / kBlockY);
}

__global__ void __launch_bounds__(kBlockX* kBlockY)
    flipKernel(const float* src, float* dst, int channels, int w, int h, int fx, int fy)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x, y = blockIdx.y * kBlockY + threadIdx.y;
    if (x < w && y < h)
        flipPixel(src, dst, channels, w, h, x, y, fx != 0, fy != 0);
}

__global__ void __launch_bounds__(kBlockX* kBlockY)
    addPassKernel(const float* pass, float* sum, int w, int h, int fx, int fy, int first)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x, y = blockIdx.y * kBlockY + threadIdx.y;
    if (x < w && y < h)
        addPassPixel(pass, sum, w, h, x, y, fx != 0, fy != 0, first != 0);
}

__global__ void __launch_bounds__(kBlockX* kBlockY)
    averagePassesKernel(const float* sum, FinalOutput out)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x, y = blockIdx.y * kBlockY + threadIdx.y;
    if (x < out.width && y < out.height)
        averagePassesPixel(sum, out, x, y);
}

} // namespace

void launchFlip(
    const float* src, float* dst, int channels, int w, int h, bool fx, bool fy, cudaStream_t stream)
{
    flipKernel<<<gridFor(w, h), dim3(kBlockX, kBlockY), 0, stream>>>(
        src, dst, channels, w, h, fx ? 1 : 0, fy ? 1 : 0);
    AFN_CUDA_CHECK_LAUNCH("flipKernel");
}

void launchAddPass(
    const float* pass, float* sum, int w, int h, bool fx, bool fy, bool first, cudaStream_t stream)
{
    addPassKernel<<<gridFor(w, h), dim3(kBlockX, kBlockY), 0, stream>>>(
        pass, sum, w, h, fx ? 1 : 0, fy ? 1 : 0, first ? 1 : 0);
    AFN_CUDA_CHECK_LAUNCH("addPassKernel");
}

void launchAveragePasses(const float* sum, const FinalOutput& out, cudaStream_t stream)
{
    averagePassesKernel<<<gridFor(out.width, out.height), dim3(kBlockX, kBlockY), 0, stream>>>(
        sum, out);
    AFN_CUDA_CHECK_LAUNCH("averagePassesKernel");
}

} // namespace afn::cuda
