// SPDX-License-Identifier: Apache-2.0
// afn's highlight bypass (highlight_pixel.h): the histogram, one thread per sampled pixel; the
// limit, one thread; the clamp, one thread per value; the excess, one thread per pixel. Compiled
// with --fmad=false (cuda/CMakeLists.txt) like the CPU's float arithmetic.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kThreads = 256;

unsigned blocksFor(long long items)
{
    return static_cast<unsigned>((items + kThreads - 1) / kThreads);
}

__global__ void __launch_bounds__(kThreads)
    histogramKernel(const float* ta, int width, int height, unsigned* counts)
{
    const int sw = highlightSamples(width), sh = highlightSamples(height);
    const long long i = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (i >= static_cast<long long>(sw) * sh)
        return;
    const int x = static_cast<int>(i % sw) * kHighlightStride;
    const int y = static_cast<int>(i / sw) * kHighlightStride;
    const float* p = ta + 3 * (static_cast<std::size_t>(y) * width + x);
    atomicAdd(counts + highlightBin(highlightLargest(p)), 1u);
}

__global__ void limitKernel(
    const unsigned* counts, long long n, const FrameConstants* frame, float* limit)
{
    if (blockIdx.x == 0 && threadIdx.x == 0)
        *limit = highlightLimitFromCounts(counts, n, frame->highlights);
}

__global__ void __launch_bounds__(kThreads)
    clampKernel(const float* in, const float* limit, float* out, long long values)
{
    const long long i = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (i < values)
        out[i] = clampHighlight(in[i], *limit);
}

__global__ void __launch_bounds__(kThreads) excessKernel(const float* ta, const float* albedo,
    bool plain, const float* limit, float* out, long long pixels)
{
    const long long i = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (i < pixels)
        addHighlightExcess(
            ta + 3 * i, albedo ? albedo + 3 * i : nullptr, plain, *limit, out + 3 * i);
}

} // namespace

void launchHighlightLimit(const float* ta, int width, int height, const FrameConstants* frame,
    unsigned* counts, float* limit, cudaStream_t stream)
{
    AFN_CUDA_CHECK(cudaMemsetAsync(counts, 0, kHighlightBins * sizeof(unsigned), stream));
    const long long n = static_cast<long long>(highlightSamples(width)) * highlightSamples(height);
    histogramKernel<<<blocksFor(n), kThreads, 0, stream>>>(ta, width, height, counts);
    AFN_CUDA_CHECK_LAUNCH("histogramKernel");
    limitKernel<<<1, 1, 0, stream>>>(counts, n, frame, limit);
    AFN_CUDA_CHECK_LAUNCH("limitKernel");
}

void launchHighlightClamp(
    const float* in, const float* limit, float* out, int width, int height, cudaStream_t stream)
{
    const long long values = 3LL * width * height;
    clampKernel<<<blocksFor(values), kThreads, 0, stream>>>(in, limit, out, values);
    AFN_CUDA_CHECK_LAUNCH("clampKernel");
}

void launchHighlightExcess(const float* ta, const float* albedo, bool plain, const float* limit,
    float* out, int width, int height, cudaStream_t stream)
{
    const long long pixels = static_cast<long long>(width) * height;
    excessKernel<<<blocksFor(pixels), kThreads, 0, stream>>>(ta, albedo, plain, limit, out, pixels);
    AFN_CUDA_CHECK_LAUNCH("excessKernel");
}

} // namespace afn::cuda
