// SPDX-License-Identifier: Apache-2.0
// Run-time kernel choice (see cpu/isa.h).
#include "cpu/isa.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace afn::cpu {

namespace {

bool cpuHasAvx512()
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f");
#else
    return false;
#endif
}

bool detectBf16()
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512bf16");
#else
    return false;
#endif
}

Isa detect()
{
    const char* env = std::getenv("AFN_CPU_ISA");
    if (env && std::strcmp(env, "portable") == 0)
        return Isa::Portable;
    return cpuHasAvx512() ? Isa::Avx512 : Isa::Portable;
}

std::atomic<int>& current()
{
    static std::atomic<int> isa { static_cast<int>(detect()) };
    return isa;
}

std::atomic<int>& currentBf16()
{
    static std::atomic<int> mode { [] {
        const char* env = std::getenv("AFN_CPU_BF16");
        const bool emulate = (env && std::strcmp(env, "emulate") == 0) || !cpuHasAvx512Bf16();
        return static_cast<int>(emulate ? Bf16Mode::Emulated : Bf16Mode::Hardware);
    }() };
    return mode;
}

} // namespace

bool cpuHasAvx512Bf16()
{
    static const bool has = detectBf16();
    return has;
}

Bf16Mode activeBf16Mode()
{
    return static_cast<Bf16Mode>(currentBf16().load(std::memory_order_relaxed));
}

void forceBf16Mode(Bf16Mode mode)
{
    if (mode == Bf16Mode::Hardware && !cpuHasAvx512Bf16())
        mode = Bf16Mode::Emulated;
    currentBf16().store(static_cast<int>(mode), std::memory_order_relaxed);
}

Isa activeIsa()
{
    return static_cast<Isa>(current().load(std::memory_order_relaxed));
}

const char* isaName(Isa isa)
{
    return isa == Isa::Avx512 ? "avx512" : "portable";
}

void forceIsa(Isa isa)
{
    if (isa == Isa::Avx512 && !cpuHasAvx512())
        isa = Isa::Portable;
    current().store(static_cast<int>(isa), std::memory_order_relaxed);
}

} // namespace afn::cpu
