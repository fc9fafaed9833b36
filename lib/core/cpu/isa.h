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
    Amx, ///< AMX tiles (TDPBF16PS, cpu/conv_amx_bf16.cpp): 16 pixels x 16 channels per tile
};

/// Whether the CPU has AVX512_BF16 (checked once).
bool cpuHasAvx512Bf16();

/// Whether AMX bf16 tiles can run: the CPU has AMX-TILE, AMX-BF16 and AVX512_BF16, the OS
/// enables the tile state (XCR0) and, on Linux, granted this process its use (arch_prctl
/// ARCH_REQ_XCOMP_PERM, asked once here).
bool cpuHasAmxBf16();

/// Amx where cpuHasAmxBf16(), else Hardware where the CPU has AVX512_BF16, else Emulated.
/// AFN_CPU_BF16=emulate selects Emulated and AFN_CPU_BF16=avx512 the VDPBF16PS kernel (Hardware)
/// on a CPU with AMX; forceBf16Mode() overrides all of these.
Bf16Mode activeBf16Mode();

/// Tests: use `mode` from now on (a mode the CPU lacks falls back: Amx to Hardware, Hardware to
/// Emulated).
void forceBf16Mode(Bf16Mode mode);

/// Name for reports: "amx", "avx512bf16" or "emulated".
const char* bf16ModeName(Bf16Mode mode);

} // namespace afn::cpu
