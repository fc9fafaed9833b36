// SPDX-License-Identifier: Apache-2.0
// The one-thread-per-item grids of the simple kernels (large.cu, quarter.cu): 256 threads per
// block, the item of a thread, and the number of blocks for a count of items.
#pragma once

namespace afn::cuda {

constexpr int kGridThreads = 256;

/// Blocks of kGridThreads for `items` threads.
inline unsigned gridBlocks(long long items)
{
    return static_cast<unsigned>((items + kGridThreads - 1) / kGridThreads);
}

/// This thread's item of a width x height grid, as (x, y); false past its end.
__device__ inline bool gridItem(int width, int height, int& x, int& y)
{
    const long long i = static_cast<long long>(blockIdx.x) * kGridThreads + threadIdx.x;
    if (i >= static_cast<long long>(width) * height)
        return false;
    x = static_cast<int>(i % width);
    y = static_cast<int>(i / width);
    return true;
}

} // namespace afn::cuda
