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

/// How the AVX-512 engine runs a bfloat16 convolution (cpu/conv_avx512_bf16.cpp).
enum class Bf16Mode {
    Hardware, ///< VDPBF16PS (AVX512_BF16): two bf16 multiply-adds per fp32 lane
    Emulated, ///< the same arithmetic with AVX-512F FMAs (same results, no faster than fp32)
};

/// Whether the CPU has AVX512_BF16 (checked once).
bool cpuHasAvx512Bf16();

/// Hardware where the CPU has AVX512_BF16, unless AFN_CPU_BF16=emulate is set or
/// forceBf16Mode(Emulated) was called; Emulated elsewhere.
Bf16Mode activeBf16Mode();

/// Tests: use `mode` from now on (Hardware is ignored where the CPU lacks it).
void forceBf16Mode(Bf16Mode mode);

} // namespace afn::cpu
