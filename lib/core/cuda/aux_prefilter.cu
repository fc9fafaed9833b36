// SPDX-License-Identifier: Apache-2.0
// The aux prefilter (aux_prefilter_pixel.h): begin and decide on one thread, flags, geometry and
// albedo one thread per pixel. Compiled with --fmad=false (cuda/CMakeLists.txt), so that its
// arithmetic is the CPU's.
#include "cuda/check.h"
#include "cuda/kernels.h"
#include "cuda/warp_ops.cuh"

namespace afn::cuda {

namespace {

constexpr int kBlockX = 16, kBlockY = 16;

__global__ void auxBeginKernel(AuxState* state, const FrameConstants* frame)
{
    for (unsigned& c : state->counts)
        c = 0u;
    if (!frame->hasHistory) { // the first frame of a history: decide again (AuxPrefilter::reset)
        state->decided = 0;
        state->hasHistory = 0;
    }
}

__global__ void __launch_bounds__(kBlockX* kBlockY) auxFlagsKernel(AuxBuffers b)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    const unsigned speckled = x < b.width && y < b.height ? auxFlagsPixel(b, x, y) : 0u;
    // Every thread of the block takes part in the warp reductions.
    for (int kind = 0; kind < 3; ++kind) {
        const unsigned n = __reduce_add_sync(kFullMask, (speckled >> kind) & 1u);
        if ((threadIdx.x & 31) == 0 && n)
            atomicAdd(&b.state->counts[kind], n);
    }
}

__global__ void auxDecideKernel(AuxBuffers b, const FrameConstants* frame)
{
    auxDecide(b, *frame);
}

__global__ void __launch_bounds__(kBlockX* kBlockY) auxGeometryKernel(AuxBuffers b)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    if (x < b.width && y < b.height)
        auxGeometryPixel(b, x, y);
}

__global__ void __launch_bounds__(kBlockX* kBlockY)
    auxAlbedoKernel(AuxBuffers b, TemporalBuffers t, const FrameConstants* frame)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    if (x < b.width && y < b.height)
        auxAlbedoPixel(b, t, *frame, x, y);
}

} // namespace

void launchAuxPrefilter(
    const AuxBuffers& b, const TemporalBuffers& t, const FrameConstants* frame, cudaStream_t stream)
{
    const dim3 block(kBlockX, kBlockY);
    const dim3 grid((b.width + kBlockX - 1) / kBlockX, (b.height + kBlockY - 1) / kBlockY);
    auxBeginKernel<<<1, 1, 0, stream>>>(b.state, frame);
    AFN_CUDA_CHECK_LAUNCH("auxBeginKernel");
    auxFlagsKernel<<<grid, block, 0, stream>>>(b);
    AFN_CUDA_CHECK_LAUNCH("auxFlagsKernel");
    auxDecideKernel<<<1, 1, 0, stream>>>(b, frame);
    AFN_CUDA_CHECK_LAUNCH("auxDecideKernel");
    if (b.normal || b.depth) {
        auxGeometryKernel<<<grid, block, 0, stream>>>(b);
        AFN_CUDA_CHECK_LAUNCH("auxGeometryKernel");
    }
    if (b.albedo) {
        auxAlbedoKernel<<<grid, block, 0, stream>>>(b, t, frame);
        AFN_CUDA_CHECK_LAUNCH("auxAlbedoKernel");
    }
}

} // namespace afn::cuda
