// SPDX-License-Identifier: Apache-2.0
// The post-filter's guide rows (post_filter.h, PostFilterGuidePlanes): a row of the frame's
// interleaved albedo, normal and depth split into planes and sanitised, in kernels cloned per
// instruction set. Compiled without FMA contraction (CMakeLists.txt): every clone gives the bits
// of the scalar formula (|n|^2 as three products summed in order, then one division by its root).
#include "methods/afn/post_filter.h"

#include "cpu/rgb_rows.h"
#include "cpu/target.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace afn::afnet {

namespace {

/// Plane k[x] = row[3 x + k] for x in [0, w), non-finite values replaced by 0.
AFN_CPU_KERNEL_CLONES void albedoRow(
    const float* row, int w, float* __restrict a0, float* __restrict a1, float* __restrict a2)
{
    cpu::deinterleaveRgbRow(row, a0, a1, a2, w);
    for (int x = 0; x < w; ++x) {
        a0[x] = std::fabs(a0[x]) <= FLT_MAX ? a0[x] : 0.0f;
        a1[x] = std::fabs(a1[x]) <= FLT_MAX ? a1[x] : 0.0f;
        a2[x] = std::fabs(a2[x]) <= FLT_MAX ? a2[x] : 0.0f;
    }
}

/// The row's unit normals and their validity: 1 where the normal is finite and |n|^2 > 0.5, else
/// the normal and its validity 0.
AFN_CPU_KERNEL_CLONES void normalRow(const float* row, int w, float* __restrict n0,
    float* __restrict n1, float* __restrict n2, float* __restrict valid)
{
    cpu::deinterleaveRgbRow(row, n0, n1, n2, w);
    for (int x = 0; x < w; ++x) {
        const float len2 = n0[x] * n0[x] + n1[x] * n1[x] + n2[x] * n2[x];
        const bool ok = len2 > 0.5f && len2 <= FLT_MAX; // not ~0, NaN or infinite
        const float inv = 1.0f / std::sqrt(ok ? len2 : 1.0f);
        n0[x] = ok ? n0[x] * inv : 0.0f;
        n1[x] = ok ? n1[x] * inv : 0.0f;
        n2[x] = ok ? n2[x] * inv : 0.0f;
        valid[x] = ok ? 1.0f : 0.0f;
    }
}

/// The row's depth, non-finite values taken as a far background (1e30).
AFN_CPU_KERNEL_CLONES void depthRow(const float* row, int w, float* __restrict z)
{
    for (int x = 0; x < w; ++x)
        z[x] = std::fabs(row[x]) <= FLT_MAX ? row[x] : 1e30f;
}

} // namespace

void buildPostFilterGuideRow(const PostFilterGuides& g, int w, int h, int y,
    const PostFilterGuidePlanes& p, std::size_t offset)
{
    auto usable = [&](const Image* im, int channels) {
        return im && im->width() == w && im->height() == h && im->channels() == channels;
    };
    const std::size_t i = offset;
    if (usable(g.albedo, 3))
        albedoRow(g.albedo->at(0, y), w, p.a0 + i, p.a1 + i, p.a2 + i);
    else
        for (float* plane : { p.a0, p.a1, p.a2 })
            std::fill(plane + i, plane + i + w, 0.0f);
    if (usable(g.normal, 3))
        normalRow(g.normal->at(0, y), w, p.n0 + i, p.n1 + i, p.n2 + i, p.nv + i);
    else
        for (float* plane : { p.n0, p.n1, p.n2, p.nv })
            std::fill(plane + i, plane + i + w, 0.0f);
    if (usable(g.depth, 1))
        depthRow(g.depth->at(0, y), w, p.z + i);
    else
        std::fill(p.z + i, p.z + i + w, 1.0f);
}

} // namespace afn::afnet
