// SPDX-License-Identifier: Apache-2.0
// Register fragments of the tensor-core instruction the CUDA engine uses,
// mma.sync.aligned.m16n8k16.row.col.f32.f16.f16.f32 (PTX ISA, "Matrix Fragments for
// mma.m16n8k16 with floating point type"). With lane = 4 g + t (g = lane / 4, t = lane % 4):
//   A (16 x 16 halves, rows = pixels, columns = K): register r holds the halves at row
//     g + 8 (r & 1) and columns c, c + 1 with c = 2t + 8 (r >> 1); column c in the low 16 bits
//   B (16 x 8 halves, rows = K, columns = output channels): register r holds rows k, k + 1 with
//     k = 2t + 8 r, column g; row k in the low 16 bits
//   C/D (16 x 8 floats): element i at row g + 8 (i >> 1), column 2t + (i & 1)
// Every kernel addresses its operands through these functions, and the host tests emulate the
// instruction with them (tests/unit/core/cuda/test_cuda_layout.cpp).
#pragma once

#include "cuda/device_math.h"

namespace afn::cuda {

struct Fragment {
    static AFN_HD int group(int lane) { return lane >> 2; }
    static AFN_HD int thread(int lane) { return lane & 3; }
    /// Row of A register `reg` (0..3).
    static AFN_HD int aRow(int lane, int reg) { return (lane >> 2) + 8 * (reg & 1); }
    /// First of the two K columns of A register `reg`.
    static AFN_HD int aCol(int lane, int reg) { return 2 * (lane & 3) + 8 * (reg >> 1); }
    /// First of the two K rows of B register `reg` (0..1).
    static AFN_HD int bRow(int lane, int reg) { return 2 * (lane & 3) + 8 * reg; }
    /// Column (output channel within the N tile) of B.
    static AFN_HD int bCol(int lane) { return lane >> 2; }
    /// Row of C element `i` (0..3).
    static AFN_HD int cRow(int lane, int i) { return (lane >> 2) + 8 * (i >> 1); }
    /// Column of C element `i`.
    static AFN_HD int cCol(int lane, int i) { return 2 * (lane & 3) + (i & 1); }
};

} // namespace afn::cuda
