// SPDX-License-Identifier: Apache-2.0
// The first stage (temporal_pixel.h): the gather and the per-frame depth range, one thread per
// pixel; the history trust (history_trust_block.h), one thread per row block, group of blocks and
// block; the blend, one thread per pixel. This file is compiled with --fmad=false
// (cuda/CMakeLists.txt) so that its arithmetic is the CPU's.
#include "cuda/check.h"
#include "cuda/kernels.h"
#include "cuda/warp_ops.cuh"

namespace afn::cuda {

namespace {

constexpr int kBlockX = 16, kBlockY = 16;

constexpr int kThreads = 256;

unsigned blocksFor(long long items)
{
    return static_cast<unsigned>((items + kThreads - 1) / kThreads);
}

__global__ void resetFrameCountersKernel(std::uint32_t* range, unsigned* cutPixels)
{
    range[0] = kEmptyRangeMin;
    range[1] = kEmptyRangeMax;
    *cutPixels = 0u;
}

__global__ void __launch_bounds__(kBlockX* kBlockY)
    temporalKernel(TemporalBuffers b, const FrameConstants* frame, std::uint32_t* depthRange)
{
    // The frame's constants, copied once per block into shared memory (as words: a __shared__
    // variable cannot have the struct's default member initialisers).
    constexpr int kWords = sizeof(FrameConstants) / sizeof(std::uint32_t);
    static_assert(sizeof(FrameConstants) % sizeof(std::uint32_t) == 0, "FrameConstants words");
    static_assert(alignof(FrameConstants) == alignof(std::uint32_t), "FrameConstants alignment");
    static_assert(kWords <= kBlockX * kBlockY, "one word per thread");
    __shared__ std::uint32_t constantWords[kWords];
    const int thread = threadIdx.y * kBlockX + threadIdx.x;
    if (thread < kWords)
        constantWords[thread] = reinterpret_cast<const std::uint32_t*>(frame)[thread];
    __syncthreads();
    const FrameConstants& constants = *reinterpret_cast<const FrameConstants*>(constantWords);
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    const bool inside = x < b.width && y < b.height;
    if (inside)
        temporalGather(b, constants, x, y);
    if (b.depth) { // uniform: every thread of the block takes part in the warp reductions
        std::uint32_t lo = kEmptyRangeMin, hi = kEmptyRangeMax;
        if (inside) {
            const float z = b.depth[static_cast<std::size_t>(y) * b.width + x];
            if (isValidDepth(z))
                lo = hi = orderedKey(z);
        }
        lo = __reduce_min_sync(kFullMask, lo);
        hi = __reduce_max_sync(kFullMask, hi);
        if ((threadIdx.x & 31) == 0 && lo != kEmptyRangeMin) {
            atomicMin(depthRange, lo);
            atomicMax(depthRange + 1, hi);
        }
    }
}

__global__ void __launch_bounds__(kThreads)
    trustRowSumsKernel(TemporalBuffers b, TrustBuffers t, const FrameConstants* frame)
{
    const long long index = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (!trustMeasured(frame->hasHistory, frame->antilag)
        || index >= static_cast<long long>(t.height) * t.blocksX)
        return;
    trustRowSums(t, b.irradiance, b.accumulated, b.historyLength,
        static_cast<int>(index / t.blocksX), static_cast<int>(index % t.blocksX));
}

__global__ void __launch_bounds__(kThreads)
    trustGroupKernel(TrustBuffers t, const FrameConstants* frame)
{
    const int groupsX = (t.blocksX + kTrustCoarse - 1) / kTrustCoarse;
    const int groupsY = (t.blocksY + kTrustCoarse - 1) / kTrustCoarse;
    const long long index = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (!trustMeasured(frame->hasHistory, frame->antilag)
        || index >= static_cast<long long>(groupsX) * groupsY)
        return;
    trustGroup(
        t, frame->antilag, static_cast<int>(index % groupsX), static_cast<int>(index / groupsX));
}

__global__ void __launch_bounds__(kThreads)
    trustSoftMinKernel(TrustBuffers t, const FrameConstants* frame)
{
    const long long index = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (!trustMeasured(frame->hasHistory, frame->antilag)
        || index >= static_cast<long long>(t.blocksX) * t.blocksY)
        return;
    const unsigned cut
        = trustSoftMin(t, static_cast<int>(index % t.blocksX), static_cast<int>(index / t.blocksX));
    if (cut)
        atomicAdd(t.cutPixels, cut);
}

__global__ void __launch_bounds__(kBlockX* kBlockY)
    blendKernel(TemporalBuffers b, TrustBuffers t, const FrameConstants* frame)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    if (x >= b.width || y >= b.height)
        return;
    const FrameConstants& f = *frame;
    const float trust = trustMeasured(f.hasHistory, f.antilag) ? pixelTrust(t, x, y) : 1.0f;
    temporalBlend(b, f, trust, x, y);
}

} // namespace

void launchResetFrameCounters(std::uint32_t* depthRange, unsigned* cutPixels, cudaStream_t stream)
{
    resetFrameCountersKernel<<<1, 1, 0, stream>>>(depthRange, cutPixels);
    AFN_CUDA_CHECK_LAUNCH("resetFrameCountersKernel");
}

void launchTemporal(const TemporalBuffers& b, const TrustBuffers& t, const FrameConstants* frame,
    std::uint32_t* depthRange, cudaStream_t stream)
{
    const dim3 block(kBlockX, kBlockY);
    const dim3 grid((b.width + kBlockX - 1) / kBlockX, (b.height + kBlockY - 1) / kBlockY);
    temporalKernel<<<grid, block, 0, stream>>>(b, frame, depthRange);
    AFN_CUDA_CHECK_LAUNCH("temporalKernel");
    trustRowSumsKernel<<<blocksFor(static_cast<long long>(t.height) * t.blocksX), kThreads, 0,
        stream>>>(b, t, frame);
    AFN_CUDA_CHECK_LAUNCH("trustRowSumsKernel");
    const long long groups = static_cast<long long>((t.blocksX + kTrustCoarse - 1) / kTrustCoarse)
        * ((t.blocksY + kTrustCoarse - 1) / kTrustCoarse);
    trustGroupKernel<<<blocksFor(groups), kThreads, 0, stream>>>(t, frame);
    AFN_CUDA_CHECK_LAUNCH("trustGroupKernel");
    trustSoftMinKernel<<<blocksFor(static_cast<long long>(t.blocksX) * t.blocksY), kThreads, 0,
        stream>>>(t, frame);
    AFN_CUDA_CHECK_LAUNCH("trustSoftMinKernel");
    blendKernel<<<grid, block, 0, stream>>>(b, t, frame);
    AFN_CUDA_CHECK_LAUNCH("blendKernel");
}

} // namespace afn::cuda
