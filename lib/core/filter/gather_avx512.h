// SPDX-License-Identifier: Apache-2.0
// Internal to filter/gather.cpp: the normal's conversion with AVX-512F (gather_avx512.cpp).
#pragma once

namespace afn {

/// The 16 packed normals at `p` (48 floats), in place: z times zSign, then divided by the length
/// (0 below 1e-12), the gather's scalar operations lane by lane (the same bits). AVX-512F only
/// (cpu::activeIsa() == Avx512).
void normalizeNormals16(float* p, float zSign);

} // namespace afn
