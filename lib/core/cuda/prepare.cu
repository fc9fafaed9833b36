// SPDX-License-Identifier: Apache-2.0
// The network input (prepare_block.h), one thread per 2 x 2 block of the padded frame; the colours
// times the albedo for a model without albedo (device_math.h undemodulateValue); and the
// 2 x 2 average pooling of half-precision tensors, one thread per output pixel and 8 channels.
// Compiled with --fmad=false (cuda/CMakeLists.txt) like the CPU's float arithmetic.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kThreads = 256;

__global__ void __launch_bounds__(kThreads) prepareKernel(PrepareBuffers b)
{
    const int wh = b.paddedWidth / 2, hh = b.paddedHeight / 2;
    const long long index = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (index >= static_cast<long long>(wh) * hh)
        return;
    const int xh = static_cast<int>(index % wh), yh = static_cast<int>(index / wh);
    const DepthScale ds = b.depth ? depthScale(b.depthRange[0], b.depthRange[1]) : DepthScale {};
    prepareBlock(b, ds, xh, yh);
}

__global__ void __launch_bounds__(kThreads) undemodulateKernel(
    const float* irradiance, const float* albedo, bool plain, float* out, long long values)
{
    const long long i = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (i < values)
        out[i] = undemodulateValue(irradiance[i], albedo[i], plain);
}

/// Average of the 8 halves in four 16-byte words, rounded to halves.
__device__ uint4 average4(const uint4& a, const uint4& b, const uint4& c, const uint4& d)
{
    const std::uint32_t wa[4] = { a.x, a.y, a.z, a.w }, wb[4] = { b.x, b.y, b.z, b.w };
    const std::uint32_t wc[4] = { c.x, c.y, c.z, c.w }, wd[4] = { d.x, d.y, d.z, d.w };
    std::uint32_t out[4];
#pragma unroll
    for (int k = 0; k < 4; ++k) {
        float v[2];
#pragma unroll
        for (int e = 0; e < 2; ++e) {
            const int s = 16 * e;
            v[e] = (fromHalf(static_cast<std::uint16_t>(wa[k] >> s))
                       + fromHalf(static_cast<std::uint16_t>(wb[k] >> s))
                       + fromHalf(static_cast<std::uint16_t>(wc[k] >> s))
                       + fromHalf(static_cast<std::uint16_t>(wd[k] >> s)))
                / 4.0f;
        }
        out[k] = packHalves(v[0], v[1]);
    }
    return make_uint4(out[0], out[1], out[2], out[3]);
}

__global__ void __launch_bounds__(kThreads)
    poolKernel(const std::uint16_t* in, int width, int height, int stride, std::uint16_t* out)
{
    const int wo = width / 2, ho = height / 2, groups = stride / 8;
    const long long index = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (index >= static_cast<long long>(wo) * ho * groups)
        return;
    const int g = static_cast<int>(index % groups);
    const long long pixel = index / groups;
    const int xo = static_cast<int>(pixel % wo), yo = static_cast<int>(pixel / wo);
    auto at = [&](int x, int y) {
        return __ldg(reinterpret_cast<const uint4*>(
            in + (static_cast<std::size_t>(y) * width + x) * stride + 8 * g));
    };
    const uint4 v = average4(at(2 * xo, 2 * yo), at(2 * xo + 1, 2 * yo), at(2 * xo, 2 * yo + 1),
        at(2 * xo + 1, 2 * yo + 1));
    *reinterpret_cast<uint4*>(out + (static_cast<std::size_t>(yo) * wo + xo) * stride + 8 * g) = v;
}

unsigned blocksFor(long long items)
{
    return static_cast<unsigned>((items + kThreads - 1) / kThreads);
}

} // namespace

void launchPrepare(const PrepareBuffers& b, cudaStream_t stream)
{
    const long long blocks = static_cast<long long>(b.paddedWidth / 2) * (b.paddedHeight / 2);
    prepareKernel<<<blocksFor(blocks), kThreads, 0, stream>>>(b);
    AFN_CUDA_CHECK_LAUNCH("prepareKernel");
}

void launchUndemodulate(const float* irradiance, const float* albedo, bool plain, float* out, int w,
    int h, cudaStream_t stream)
{
    const long long values = 3LL * w * h;
    undemodulateKernel<<<blocksFor(values), kThreads, 0, stream>>>(
        irradiance, albedo, plain, out, values);
    AFN_CUDA_CHECK_LAUNCH("undemodulateKernel");
}

void launchPool(const std::uint16_t* in, int width, int height, int stride, std::uint16_t* out,
    cudaStream_t stream)
{
    const long long items = static_cast<long long>(width / 2) * (height / 2) * (stride / 8);
    poolKernel<<<blocksFor(items), kThreads, 0, stream>>>(in, width, height, stride, out);
    AFN_CUDA_CHECK_LAUNCH("poolKernel");
}

} // namespace afn::cuda
