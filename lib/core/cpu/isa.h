// SPDX-License-Identifier: Apache-2.0
// Run-time choice of the AFN engine's kernels. The build never assumes an instruction set
// (no -march): AVX-512 kernels are compiled per function (target attribute, cpu/avx512.h) and used
// only where the running CPU has AVX-512F; every other machine runs the portable kernels
// (cpu/target.h clones: x86-64-v3 or baseline). AFN_CPU_ISA=portable in the environment, or
// forceIsa() in tests, selects the portable kernels on an AVX-512 machine.
#pragma once

namespace afn::cpu {

/// Kernel families of the convolution engine.
enum class Isa {
    Portable, ///< GCC vector extensions, 8 lanes, cloned for x86-64-v3 and baseline
    Avx512, ///< hand-written AVX-512F micro-kernels, 16 lanes (cpu/conv_avx512.cpp)
};

/// The family in use: AVX-512 where the CPU has it (checked once) unless AFN_CPU_ISA=portable.
Isa activeIsa();

/// Name for reports: "avx512" or "portable".
const char* isaName(Isa isa);

/// Tests and benchmarks: use `isa` from now on (Avx512 is ignored where the CPU lacks it).
void forceIsa(Isa isa);

} // namespace afn::cpu
