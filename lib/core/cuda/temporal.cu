// SPDX-License-Identifier: Apache-2.0
// The first stage (temporal_pixel.h) and the per-frame depth range, one thread per pixel. This
// file is compiled with --fmad=false (cuda/CMakeLists.txt) so that its arithmetic is the CPU's.
#include "cuda/check.h"
#include "cuda/kernels.h"
#include "cuda/warp_ops.cuh"

namespace afn::cuda {

namespace {

constexpr int kBlockX = 16, kBlockY = 16;

__global__ void resetDepthRangeKernel(std::uint32_t* range)
{
    range[0] = kEmptyRangeMin;
    range[1] = kEmptyRangeMax;
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
        temporalPixel(b, constants, x, y);
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

} // namespace

void launchResetDepthRange(std::uint32_t* depthRange, cudaStream_t stream)
{
    resetDepthRangeKernel<<<1, 1, 0, stream>>>(depthRange);
    AFN_CUDA_CHECK_LAUNCH("resetDepthRangeKernel");
}

void launchTemporal(const TemporalBuffers& b, const FrameConstants* frame,
    std::uint32_t* depthRange, cudaStream_t stream)
{
    const dim3 block(kBlockX, kBlockY);
    const dim3 grid((b.width + kBlockX - 1) / kBlockX, (b.height + kBlockY - 1) / kBlockY);
    temporalKernel<<<grid, block, 0, stream>>>(b, frame, depthRange);
    AFN_CUDA_CHECK_LAUNCH("temporalKernel");
}

} // namespace afn::cuda
