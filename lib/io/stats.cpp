// SPDX-License-Identifier: Apache-2.0
// Per-role statistics for --info: range and mean of the finite values, non-finite counts.
#include "afn/io.hpp"

#include <cmath>
#include <limits>

namespace afn::io {

// count = every value examined (pixels x components); min/max/mean over the finite ones only (all
// 0 when there are none); negative counts finite values below 0 (-Inf counts as Inf).
RoleStats computeStats(const RoleImage& image)
{
    RoleStats s;
    double sum = 0.0;
    long long finite = 0;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (float v : image.pixels) {
        ++s.count;
        if (std::isnan(v)) {
            ++s.nan;
        } else if (std::isinf(v)) {
            ++s.inf;
        } else {
            ++finite;
            sum += v;
            lo = std::min(lo, static_cast<double>(v));
            hi = std::max(hi, static_cast<double>(v));
            if (v < 0.0f)
                ++s.negative;
        }
    }
    if (finite > 0) {
        s.min = lo;
        s.max = hi;
        s.mean = sum / static_cast<double>(finite);
    }
    return s;
}

} // namespace afn::io
