// SPDX-License-Identifier: Apache-2.0
// The one parallel-for of the core. Work is split into fixed row blocks, so every pixel's result is
// computed by the same code whatever the thread count: outputs are bit-identical across counts.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace afn {

/// Call fn(y0, y1) over [0, height) in blocks of `grain` rows, in parallel.
template <typename Fn> void parallelRows(int height, Fn&& fn, int grain = 8)
{
    tbb::parallel_for(
        tbb::blocked_range<int>(0, height, grain),
        [&](const tbb::blocked_range<int>& r) { fn(r.begin(), r.end()); },
        tbb::simple_partitioner());
}

/// Call fn(i) for i in [0, n), in parallel.
template <typename Fn> void parallelFor(int n, Fn&& fn)
{
    tbb::parallel_for(0, n, [&](int i) { fn(i); });
}

} // namespace afn
