// SPDX-License-Identifier: Apache-2.0
// Internal to filter/gather.cpp: the gather's per-value operations (GatherOp, shared by the
// portable code and the AVX-512F kernels) and its AVX-512F kernels (gather_avx512.cpp).
#pragma once

#include <cfloat>
#include <cmath>
#include <cstdint>

namespace afn {

/// What the gather does to each value of one input after replacing a non-finite value by
/// `replacement`: the same operations, value by value, in the portable and the AVX-512 code.
struct GatherOp {
    enum class Kind {
        Copy, ///< as read (depth, position, alpha; normals are converted per row afterwards)
        NonNegative, ///< colour: v < 0 becomes 0 (-0 stays -0), counted as negative
        Unit, ///< albedo: v < 0 ? 0 : (v > 1 ? 1 : v) (-0 stays -0)
        Scale2, ///< motion: values alternate x, y: x * sx, y * sy
    };
    Kind kind = Kind::Copy;
    float replacement = 0.0f; ///< for NaN and +-Inf
    float sx = 1.0f, sy = 1.0f; ///< Scale2 only
};

/// Non-finite and negative values counted by a gather.
struct GatherCounts {
    std::int64_t nonFinite = 0;
    std::int64_t negative = 0;
};

/// One value: `channel` is the value's channel (its index in the pixel).
inline float gatherValue(float v, int channel, const GatherOp& op, GatherCounts& counts)
{
    const bool finite = std::fabs(v) <= FLT_MAX; // false for NaN and +-Inf
    counts.nonFinite += finite ? 0 : 1;
    v = finite ? v : op.replacement;
    switch (op.kind) {
    case GatherOp::Kind::Copy:
        break;
    case GatherOp::Kind::NonNegative:
        counts.negative += v < 0.0f ? 1 : 0;
        v = v < 0.0f ? 0.0f : v;
        break;
    case GatherOp::Kind::Unit:
        v = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
        break;
    case GatherOp::Kind::Scale2:
        v *= (channel & 1) ? op.sy : op.sx;
        break;
    }
    return v;
}

/// `n` packed values from `s` to `d` through gatherValue (value i of channel i % 2 for Scale2,
/// which needs runs that start at a pixel), 16 at a time with masked loads and stores for the
/// tail: the same bits and counts as the scalar code. AVX-512F only (cpu::activeIsa() == Avx512).
/// `stream`: whole aligned vectors are written with streaming stores (for a run no one reads
/// soon); false keeps the run in cache for a conversion that reads it next (normals, the colour's
/// demodulation).
void gatherRunAvx512(
    const float* s, float* d, int n, const GatherOp& op, GatherCounts& counts, bool stream = true);

/// The 16 packed normals at `p` (48 floats), in place: z times zSign, then divided by the length
/// (0 below 1e-12), the gather's scalar operations lane by lane (the same bits). AVX-512F only
/// (cpu::activeIsa() == Avx512).
void normalizeNormals16(float* p, float zSign);

} // namespace afn
