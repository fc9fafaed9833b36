// SPDX-License-Identifier: Apache-2.0
// Convolution layers on tensor cores (implicit GEMM, conv_tile.h): each warp computes 16
// consecutive output pixels of one row for up to kMaxTilesPerWarp N tiles; K runs over the taps
// and 16-channel chunks; the weights are read through the read-only cache (a layer's weights are
// a few tens of kilobytes, shared by every warp). Wider layers split their N tiles over gridDim.y.
#include "cuda/check.h"
#include "cuda/kernels.h"
#include "cuda/warp_ops.cuh"

namespace afn::cuda {

namespace {

constexpr int kWarpsPerBlock = 4;
constexpr int kMaxTilesPerWarp = 8;

/// Epilogue of a hidden layer.
struct ReluEpilogue {
    ReluOutput out;
    __device__ void store(
        const ConvOperands& op, int lane, int x0, int y, int tile, const float (&c)[4]) const
    {
        storeRelu(op, out, lane, x0, y, tile, c);
    }
    __device__ void finish(const ConvOperands& op, int lane, int x0, int y) const
    {
        storeZeroPadding(op, out, lane, x0, y);
    }
};

/// Epilogue of a layer without activation (float output).
struct LinearEpilogue {
    LinearOutput out;
    __device__ void store(
        const ConvOperands& op, int lane, int x0, int y, int tile, const float (&c)[4]) const
    {
        storeLinear(op, out, lane, x0, y, tile, c);
    }
    __device__ void finish(const ConvOperands&, int, int, int) const { }
};

/// Epilogue of the last refinement layer (one N tile).
struct FinalEpilogue {
    FinalOutput out;
    __device__ void store(
        const ConvOperands& op, int lane, int x0, int y, int tile, const float (&c)[4]) const
    {
        if (tile == 0)
            storeFinal(op, out, lane, x0, y, c);
    }
    __device__ void finish(const ConvOperands&, int, int, int) const { }
};

template <int kTiles, typename Epilogue>
__global__ void __launch_bounds__(kWarpsPerBlock * 32) convKernel(ConvOperands op, Epilogue epi)
{
    const int lane = threadIdx.x & 31;
    const int warp = blockIdx.x * kWarpsPerBlock + (threadIdx.x >> 5);
    const int tilesPerRow = (op.width + 15) / 16;
    if (warp >= tilesPerRow * op.height) // the whole warp leaves together
        return;
    const int y = warp / tilesPerRow, x0 = (warp % tilesPerRow) * 16;
    const int tile0 = blockIdx.y * kTiles;
    float acc[kTiles][4];
#pragma unroll
    for (int j = 0; j < kTiles; ++j)
        acc[j][0] = acc[j][1] = acc[j][2] = acc[j][3] = 0.0f;
    const int taps = op.ksize * op.ksize, kChunks = op.kChunks();
    for (int tap = 0; tap < taps; ++tap)
        for (int kc = 0; kc < kChunks; ++kc) {
            std::uint32_t a[4];
            loadConvA(op, TileShape::Row16, lane, x0, y, tap, kc, a);
#pragma unroll
            for (int j = 0; j < kTiles; ++j)
                if (tile0 + j < op.tiles) {
                    std::uint32_t b[2];
                    loadConvB(op, lane, tap, kc, tile0 + j, b);
                    mmaM16N8K16(acc[j], a, b);
                }
        }
#pragma unroll
    for (int j = 0; j < kTiles; ++j)
        if (tile0 + j < op.tiles)
            epi.store(op, lane, x0, y, tile0 + j, acc[j]);
    if (blockIdx.y == 0)
        epi.finish(op, lane, x0, y);
}

template <int kTiles, typename Epilogue>
void launch(const ConvOperands& op, const Epilogue& epi, int groups, cudaStream_t stream)
{
    const long long warps = static_cast<long long>((op.width + 15) / 16) * op.height;
    const dim3 grid(static_cast<unsigned>((warps + kWarpsPerBlock - 1) / kWarpsPerBlock),
        static_cast<unsigned>(groups));
    convKernel<kTiles, Epilogue><<<grid, kWarpsPerBlock * 32, 0, stream>>>(op, epi);
    AFN_CUDA_CHECK_LAUNCH("convKernel");
}

void checkOperands(const ConvOperands& op)
{
    if (op.width <= 0 || op.height <= 0 || op.tiles <= 0 || !op.same || !op.weights || !op.bias
        || (op.ksize != 1 && op.ksize != 3) || (op.upChunks > 0 && !op.up))
        throwCudaError(cudaErrorInvalidValue, "convolution operands", __FILE__, __LINE__);
}

/// Every N tile of the layer: up to kMaxTilesPerWarp per warp, split evenly over gridDim.y.
template <typename Epilogue>
void launchTiles(const ConvOperands& op, const Epilogue& epi, cudaStream_t stream)
{
    const int groups = (op.tiles + kMaxTilesPerWarp - 1) / kMaxTilesPerWarp;
    switch ((op.tiles + groups - 1) / groups) {
    case 1:
        return launch<1>(op, epi, groups, stream);
    case 2:
        return launch<2>(op, epi, groups, stream);
    case 3:
        return launch<3>(op, epi, groups, stream);
    case 4:
        return launch<4>(op, epi, groups, stream);
    case 5:
        return launch<5>(op, epi, groups, stream);
    case 6:
        return launch<6>(op, epi, groups, stream);
    case 7:
        return launch<7>(op, epi, groups, stream);
    default:
        return launch<8>(op, epi, groups, stream);
    }
}

} // namespace

void launchConvRelu(const ConvOperands& op, const ReluOutput& out, cudaStream_t stream)
{
    checkOperands(op);
    launchTiles(op, ReluEpilogue { out }, stream);
}

void launchConvLinear(const ConvOperands& op, const LinearOutput& out, cudaStream_t stream)
{
    checkOperands(op);
    if (!out.data || out.channels <= 0 || out.channels > op.tiles * kTileN)
        throwCudaError(cudaErrorInvalidValue, "linear convolution output", __FILE__, __LINE__);
    launchTiles(op, LinearEpilogue { out }, stream);
}

void launchConvFinal(const ConvOperands& op, const FinalOutput& out, cudaStream_t stream)
{
    checkOperands(op);
    if (op.tiles != 1 || !out.fused || !out.data)
        throwCudaError(cudaErrorInvalidValue, "final convolution operands", __FILE__, __LINE__);
    launch<1>(op, FinalEpilogue { out }, 1, stream);
}

} // namespace afn::cuda
