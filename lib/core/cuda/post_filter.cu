// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (post_filter_pixel.h): the guide planes, then six half-passes, one
// thread per pixel each. Compiled with --fmad=false (cuda/CMakeLists.txt) like the CPU's guides
// and noise scale; the half-passes so compute what the CPU's clones without fused multiply-adds
// compute.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kBlockX = 16, kBlockY = 16;

__global__ void __launch_bounds__(kBlockX* kBlockY)
    postFilterGuideKernel(PostFilterSources s, PostFilterPlanes g, const FrameConstants* frame)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    s.maxSamples = effectiveSamplesLimit(frame->alphaMin);
    if (x < s.width && y < s.height)
        postFilterGuidePixel(s, g, x, y);
}

__global__ void __launch_bounds__(kBlockX* kBlockY) postFilterHalfKernel(
    PostFilterPlanes g, const float* in, float* out, int w, int h, int horizontal, int step)
{
    const int x = blockIdx.x * kBlockX + threadIdx.x;
    const int y = blockIdx.y * kBlockY + threadIdx.y;
    if (x < w && y < h)
        postFilterHalfPixel(g, in, out, w, h, x, y, horizontal != 0, step);
}

} // namespace

void launchPostFilter(const PostFilterSources& s, const PostFilterPlanes& g,
    const FrameConstants* frame, const float* input, float* output, float* scratch0,
    float* scratch1, cudaStream_t stream)
{
    const dim3 block(kBlockX, kBlockY);
    const dim3 grid((s.width + kBlockX - 1) / kBlockX, (s.height + kBlockY - 1) / kBlockY);
    postFilterGuideKernel<<<grid, block, 0, stream>>>(s, g, frame);
    AFN_CUDA_CHECK_LAUNCH("postFilterGuideKernel");
    // input -> 0 -> 1 -> 0 -> 1 -> 0 -> output
    const float* in = input;
    for (int pass = 0; pass < kPostFilterIterationsDevice; ++pass)
        for (int half = 0; half < 2; ++half) {
            const bool last = pass == kPostFilterIterationsDevice - 1 && half == 1;
            float* out = last ? output : (half == 0 ? scratch0 : scratch1);
            postFilterHalfKernel<<<grid, block, 0, stream>>>(
                g, in, out, s.width, s.height, half == 0 ? 1 : 0, 1 << pass);
            AFN_CUDA_CHECK_LAUNCH("postFilterHalfKernel");
            in = out;
        }
}

} // namespace afn::cuda
