// SPDX-License-Identifier: Apache-2.0
// Device-only warp operations of the CUDA engine: the tensor-core instruction and the reductions
// over the 4 lanes of a quad (lanes 4g .. 4g + 3 hold one pixel's head accumulators).
#pragma once

#include <cstdint>

namespace afn::cuda {

constexpr unsigned kFullMask = 0xffffffffu;

/// c += A * B with mma.sync.aligned.m16n8k16.row.col.f32.f16.f16.f32 (fragments in fragment.h).
__device__ __forceinline__ void mmaM16N8K16(
    float (&c)[4], const std::uint32_t (&a)[4], const std::uint32_t (&b)[2])
{
    asm("mma.sync.aligned.m16n8k16.row.col.f32.f16.f16.f32 {%0, %1, %2, %3}, {%4, %5, %6, %7}, "
        "{%8, %9}, {%0, %1, %2, %3};\n"
        : "+f"(c[0]), "+f"(c[1]), "+f"(c[2]), "+f"(c[3])
        : "r"(a[0]), "r"(a[1]), "r"(a[2]), "r"(a[3]), "r"(b[0]), "r"(b[1]));
}

/// Sum over the quad by a butterfly (every lane of the quad gets the same bits).
__device__ __forceinline__ float quadSum(float v)
{
    v += __shfl_xor_sync(kFullMask, v, 1);
    v += __shfl_xor_sync(kFullMask, v, 2);
    return v;
}

/// Maximum over the quad.
__device__ __forceinline__ float quadMax(float v)
{
    v = fmaxf(v, __shfl_xor_sync(kFullMask, v, 1));
    v = fmaxf(v, __shfl_xor_sync(kFullMask, v, 2));
    return v;
}

} // namespace afn::cuda
