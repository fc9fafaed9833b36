// SPDX-License-Identifier: Apache-2.0
// Every CUDA runtime call of the engine goes through AFN_CUDA_CHECK, and every kernel launch is
// followed by AFN_CUDA_CHECK_LAUNCH: a failure throws afn::Exception naming the call, the source
// line and CUDA's error name and text (out of memory -> AFN_ERROR_OUT_OF_MEMORY, no usable GPU ->
// AFN_ERROR_UNSUPPORTED, anything else -> AFN_ERROR_UNKNOWN).
#pragma once

#include <cuda_runtime_api.h>

namespace afn::cuda {

[[noreturn]] void throwCudaError(cudaError_t error, const char* what, const char* file, int line);

inline void checkCuda(cudaError_t error, const char* what, const char* file, int line)
{
    if (error != cudaSuccess)
        throwCudaError(error, what, file, line);
}

/// After a kernel launch: the launch error, if any (cudaGetLastError, which also clears it).
void checkLaunch(const char* kernel, const char* file, int line);

} // namespace afn::cuda

#define AFN_CUDA_CHECK(call) ::afn::cuda::checkCuda((call), #call, __FILE__, __LINE__)
#define AFN_CUDA_CHECK_LAUNCH(kernel) ::afn::cuda::checkLaunch(kernel, __FILE__, __LINE__)
