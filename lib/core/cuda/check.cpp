// SPDX-License-Identifier: Apache-2.0
#include "cuda/check.h"

#include "base/exception.h"

#include <string>

namespace afn::cuda {

void throwCudaError(cudaError_t error, const char* what, const char* file, int line)
{
    std::string where = file;
    const std::size_t slash = where.find_last_of('/');
    if (slash != std::string::npos)
        where = where.substr(slash + 1);
    const std::string message = std::string("CUDA error in ") + what + " (" + where + ":"
        + std::to_string(line) + "): " + cudaGetErrorName(error) + ": " + cudaGetErrorString(error);
    AFNError code = AFN_ERROR_UNKNOWN;
    if (error == cudaErrorMemoryAllocation)
        code = AFN_ERROR_OUT_OF_MEMORY;
    else if (error == cudaErrorNoDevice || error == cudaErrorInsufficientDriver)
        code = AFN_ERROR_UNSUPPORTED;
    throw Exception(code, message);
}

void checkLaunch(const char* kernel, const char* file, int line)
{
    const cudaError_t error = cudaGetLastError();
    if (error != cudaSuccess)
        throwCudaError(error, (std::string("launch of ") + kernel).c_str(), file, line);
}

} // namespace afn::cuda
