// SPDX-License-Identifier: Apache-2.0
#include "cuda/gpu.h"

#include "base/exception.h"
#include "cuda/check.h"

#include <cuda_runtime_api.h>

namespace afn::cuda {

namespace {

/// Kernels are compiled for compute capability 9.0 (sm_90 code and compute_90 PTX).
constexpr int kMinimumMajor = 9;

[[noreturn]] void unsupported(const std::string& why)
{
    throw Exception(AFN_ERROR_UNSUPPORTED, "no usable CUDA GPU: " + why);
}

} // namespace

GpuInfo findGpu()
{
    int count = 0;
    const cudaError_t error = cudaGetDeviceCount(&count);
    if (error != cudaSuccess) {
        cudaGetLastError(); // not sticky; leave no error behind
        unsupported(std::string(cudaGetErrorName(error)) + ": " + cudaGetErrorString(error));
    }
    if (count == 0)
        unsupported("the CUDA driver reports no GPU");
    std::string seen;
    for (int i = 0; i < count; ++i) {
        cudaDeviceProp prop {};
        AFN_CUDA_CHECK(cudaGetDeviceProperties(&prop, i));
        if (prop.major >= kMinimumMajor) {
            GpuInfo info;
            info.ordinal = i;
            info.name = prop.name;
            info.major = prop.major;
            info.minor = prop.minor;
            info.multiprocessors = prop.multiProcessorCount;
            info.memoryBytes = prop.totalGlobalMem;
            return info;
        }
        seen += (seen.empty() ? "" : ", ") + std::string(prop.name) + " (compute capability "
            + std::to_string(prop.major) + "." + std::to_string(prop.minor) + ")";
    }
    unsupported("this build's kernels need compute capability 9.0 or newer; found " + seen);
}

void useGpu(int ordinal)
{
    AFN_CUDA_CHECK(cudaSetDevice(ordinal));
}

} // namespace afn::cuda
