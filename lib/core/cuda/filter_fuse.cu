// SPDX-License-Identifier: Apache-2.0
// The fused heads + softmax + 7 x 7 filtering + Eq. 3 (methods/afn/fusion.h) on tensor cores. One
// warp takes a strip of 16 half-resolution pixels (xh0 .. xh0 + 15, row yh), i.e. 32 x 2
// full-resolution pixels:
//   1. head1 on the strip (one Row16 tile): softmax, filter D(1-spp colour) at half resolution;
//      the 16 filtered pixels go to shared memory.
//   2. four Block8x2 tiles of 8 x 2 full-resolution pixels: headTA on concat(U(d1), x), alpha,
//      softmax, filter the TA colour; the 2 x 2 block mean through the horizontal neighbour's lane
//      (lane ^ 4); Eq. 3 with the block's half-resolution result; store.
// Every pixel's 49 taps are spread over the 4 lanes of a quad (filter_fuse_lane.h); the quad's
// partial results are combined with butterfly shuffles, so all 4 lanes hold identical values.
#include "cuda/check.h"
#include "cuda/kernels.h"
#include "cuda/warp_ops.cuh"

namespace afn::cuda {

namespace {

constexpr int kWarpsPerBlock = 4;
constexpr int kStripWidth = 16; ///< half-resolution pixels per warp
// The alpha logit is column 49 = 8 * 6 + 1: tile 6, element 2 * half + 1 of the quad's lane 0.
constexpr int kAlphaTile = 6;
static_assert(kAlphaColumn == kAlphaTile * kTileN + 1, "alpha logit position");

/// Logits of one head for a tile.
__device__ void headLogits(
    const ConvOperands& op, TileShape shape, int lane, int x0, int y0, HeadAccumulators& h)
{
#pragma unroll
    for (int nt = 0; nt < kHeadTiles; ++nt)
        h.v[nt][0] = h.v[nt][1] = h.v[nt][2] = h.v[nt][3] = 0.0f;
    const int kChunks = op.kChunks();
    for (int kc = 0; kc < kChunks; ++kc) {
        std::uint32_t a[4];
        loadConvA(op, shape, lane, x0, y0, 0, kc, a);
#pragma unroll
        for (int nt = 0; nt < kHeadTiles; ++nt) {
            std::uint32_t b[2];
            loadConvB(op, lane, 0, kc, nt, b);
            mmaM16N8K16(h.v[nt], a, b);
        }
    }
    addHeadBias(h, op.bias, lane);
}

/// Softmax over the taps of tile row half `half` and the filtered colour at (x, y).
template <typename Color>
__device__ void softmaxFilter(
    HeadAccumulators& h, int lane, int half, const Color& color, int x, int y, float (&rgb)[3])
{
    const float m = quadMax(lanePartialMax(h, lane, half));
    const float s = quadSum(laneExpSum(h, lane, half, m));
    laneFilter(h, lane, half, 1.0f / s, color, x, y, rgb);
#pragma unroll
    for (int c = 0; c < 3; ++c)
        rgb[c] = quadSum(rgb[c]);
}

__global__ void __launch_bounds__(kWarpsPerBlock * 32) filterFuseKernel(FilterFuseArgs a)
{
    __shared__ float filtered1[kWarpsPerBlock][kStripWidth][3];
    const int lane = threadIdx.x & 31, warpInBlock = threadIdx.x >> 5;
    const int warp = blockIdx.x * kWarpsPerBlock + warpInBlock;
    const int halfWidth = a.head1.width, halfHeight = a.head1.height;
    const int stripsPerRow = (halfWidth + kStripWidth - 1) / kStripWidth;
    if (warp >= stripsPerRow * halfHeight) // the whole warp leaves together
        return;
    const int yh = warp / stripsPerRow, xh0 = (warp % stripsPerRow) * kStripWidth;
    const int g = Fragment::group(lane), t = Fragment::thread(lane);

    // 1. The 1-spp branch at half resolution.
    {
        HeadAccumulators h;
        headLogits(a.head1, TileShape::Row16, lane, xh0, yh, h);
#pragma unroll
        for (int half = 0; half < 2; ++half) {
            float rgb[3];
            softmaxFilter(h, lane, half, a.color1Half, xh0 + g + 8 * half, yh, rgb);
            if (t == 0)
#pragma unroll
                for (int c = 0; c < 3; ++c)
                    filtered1[warpInBlock][g + 8 * half][c] = rgb[c];
        }
    }
    __syncwarp();

    // 2. The TA branch on four 8 x 2 tiles; row half 0 is image row y0, half 1 is y0 + 1.
    const int paddedWidth = a.headTa.width;
    const int y0 = 2 * yh;
    for (int s = 0; s < 4; ++s) {
        __syncwarp(); // reconverge after the previous tile's stores: mma.sync needs the whole warp
        const int x0 = 2 * xh0 + 8 * s, x = x0 + g;
        HeadAccumulators h;
        headLogits(a.headTa, TileShape::Block8x2, lane, x0, y0, h);
        float alpha[2], dTa[2][3];
#pragma unroll
        for (int half = 0; half < 2; ++half) {
            alpha[half] = sigmoid(__shfl_sync(kFullMask, h.v[kAlphaTile][2 * half + 1], lane & ~3));
            softmaxFilter(h, lane, half, a.colorTa, x, y0 + half, dTa[half]);
        }
        // The horizontal neighbour of the 2 x 2 block is in lane ^ 4 (group g ^ 1).
        float other[2][3];
#pragma unroll
        for (int half = 0; half < 2; ++half)
#pragma unroll
            for (int c = 0; c < 3; ++c)
                other[half][c] = __shfl_xor_sync(kFullMask, dTa[half][c], 4);
        if (x >= paddedWidth)
            continue;
        const bool left = (g & 1) == 0;
        const float* d1 = filtered1[warpInBlock][4 * s + g / 2];
        float fused[2][3];
#pragma unroll
        for (int c = 0; c < 3; ++c) {
            const float tl = left ? dTa[0][c] : other[0][c], tr = left ? other[0][c] : dTa[0][c];
            const float bl = left ? dTa[1][c] : other[1][c], br = left ? other[1][c] : dTa[1][c];
#pragma unroll
            for (int half = 0; half < 2; ++half)
                fused[half][c] = fuse(dTa[half][c], alpha[half], tl, tr, bl, br, d1[c]);
        }
#pragma unroll
        for (int half = 0; half < 2; ++half) {
            const int y = y0 + half;
            const std::size_t pixel = static_cast<std::size_t>(y) * paddedWidth + x;
            if (a.fused) {
                if (t < 3)
                    a.fused[3 * pixel + t] = component(fused[half], t);
                const std::uint16_t* xPixel = a.x + pixel * kInputStride;
                std::uint32_t w[2];
#pragma unroll
                for (int k = 0; k < 2; ++k)
                    w[k] = static_cast<std::uint32_t>(
                               refineInputChannel(4 * t + 2 * k, fused[half], xPixel))
                        | (static_cast<std::uint32_t>(
                               refineInputChannel(4 * t + 2 * k + 1, fused[half], xPixel))
                            << 16);
                *reinterpret_cast<uint2*>(a.refineInput + pixel * kInputStride + 4 * t)
                    = make_uint2(w[0], w[1]);
            } else if (t < 3 && x < a.output.width && y < a.output.height) {
                const std::size_t p = static_cast<std::size_t>(y) * a.output.width + x;
                a.output.data[3 * p + t]
                    = outputValue(a.output, x, y, t, component(fused[half], t));
            }
        }
    }
}

} // namespace

void launchFilterFuse(const FilterFuseArgs& a, cudaStream_t stream)
{
    if (a.head1.tiles != kHeadTiles || a.headTa.tiles != kHeadTiles || a.headTa.sameChunks != 1
        || a.headTa.width != 2 * a.head1.width || a.headTa.height != 2 * a.head1.height
        || (!a.fused && !a.output.data) || (a.fused && !a.refineInput))
        throwCudaError(cudaErrorInvalidValue, "filter and fusion operands", __FILE__, __LINE__);
    const long long warps
        = static_cast<long long>((a.head1.width + kStripWidth - 1) / kStripWidth) * a.head1.height;
    const unsigned blocks = static_cast<unsigned>((warps + kWarpsPerBlock - 1) / kWarpsPerBlock);
    filterFuseKernel<<<blocks, kWarpsPerBlock * 32, 0, stream>>>(a);
    AFN_CUDA_CHECK_LAUNCH("filterFuseKernel");
}

} // namespace afn::cuda
