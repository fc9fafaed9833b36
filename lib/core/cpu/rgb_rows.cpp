// SPDX-License-Identifier: Apache-2.0
// See cpu/rgb_rows.h.
#include "cpu/rgb_rows.h"

#include "cpu/target.h"

namespace afn::cpu {

AFN_CPU_KERNEL_CLONES void interleaveRgbRow(
    const float* r, const float* g, const float* b, float* dst, int x0, int x1)
{
    for (int x = x0; x < x1; ++x) {
        dst[3 * x] = r[x];
        dst[3 * x + 1] = g[x];
        dst[3 * x + 2] = b[x];
    }
}

AFN_CPU_KERNEL_CLONES void deinterleaveRgbRow(const float* src, float* r, float* g, float* b, int w)
{
    for (int x = 0; x < w; ++x) {
        r[x] = src[3 * x];
        g[x] = src[3 * x + 1];
        b[x] = src[3 * x + 2];
    }
}

} // namespace afn::cpu
