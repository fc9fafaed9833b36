// SPDX-License-Identifier: Apache-2.0
// The learned albedo trust (albedo_trust_block.h), one thread per 2 x 2 block of the padded frame.
// Compiled with --fmad=false (cuda/CMakeLists.txt): s and the scaled colours repeat the CPU's
// float arithmetic operation for operation.
#include "cuda/check.h"
#include "cuda/kernels.h"

namespace afn::cuda {

namespace {

constexpr int kThreads = 256;

__global__ void __launch_bounds__(kThreads) albedoTrustKernel(AlbedoTrustBuffers b)
{
    const long long index = static_cast<long long>(blockIdx.x) * kThreads + threadIdx.x;
    if (index >= static_cast<long long>(b.halfWidth) * b.halfHeight)
        return;
    albedoTrustBlock(
        b, static_cast<int>(index % b.halfWidth), static_cast<int>(index / b.halfWidth));
}

} // namespace

void launchAlbedoTrust(const AlbedoTrustBuffers& b, cudaStream_t stream)
{
    const long long blocks = static_cast<long long>(b.halfWidth) * b.halfHeight;
    albedoTrustKernel<<<static_cast<unsigned>((blocks + kThreads - 1) / kThreads), kThreads, 0,
        stream>>>(b);
    AFN_CUDA_CHECK_LAUNCH("albedoTrustKernel");
}

} // namespace afn::cuda
