// SPDX-License-Identifier: Apache-2.0
// The GPU behind a CUDA device: found once when the device is created.
#pragma once

#include <cstddef>
#include <string>

namespace afn::cuda {

/// What the CUDA device runs on.
struct GpuInfo {
    int ordinal = -1; ///< CUDA device index
    std::string name;
    int major = 0; ///< compute capability
    int minor = 0;
    int multiprocessors = 0;
    std::size_t memoryBytes = 0;
};

/// The first GPU that can run this build's kernels (compute capability 9.0 or newer). Throws
/// afn::Exception with AFN_ERROR_UNSUPPORTED saying why there is none (no driver, no GPU, or only
/// older GPUs, each named).
GpuInfo findGpu();

/// Make GPU `ordinal` current on the calling thread (CUDA keeps the current GPU per thread, and
/// afn's calls may come from any thread).
void useGpu(int ordinal);

} // namespace afn::cuda
