// SPDX-License-Identifier: Apache-2.0
// The one guard of the CPU kernels' instruction sets. A function marked AFN_CPU_CLONES is compiled
// for x86-64-v3 (AVX2 + FMA) and for the baseline, and the loader picks the clone the machine runs
// (GCC/Clang ifunc). Elsewhere (other compilers or architectures) it is compiled once. Clones may
// differ in the last bit (FMA contraction); every accuracy test holds for both. The AVX-512
// kernels, chosen at run time instead, are marked with cpu/avx512.h.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(AFN_NO_CPU_CLONES)
#define AFN_CPU_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
// Kernels that gain from AVX-512's 32 vector registers (and mask compares) even at 8 lanes also get
// an x86-64-v4 clone (AVX-512 F/BW/CD/DQ/VL), chosen at load time like the others.
#define AFN_CPU_KERNEL_CLONES                                                                      \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define AFN_CPU_CLONES
#define AFN_CPU_KERNEL_CLONES
#endif
