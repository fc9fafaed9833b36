// SPDX-License-Identifier: Apache-2.0
// Run-time kernel choice (see cpu/isa.h).
#include "cpu/isa.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#endif
#if defined(__linux__)
#include <sys/syscall.h>
#include <unistd.h>
#endif

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

bool detectAmxBf16()
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (!__get_cpuid_count(7, 0, &a, &b, &c, &d))
        return false;
    const bool amxBf16 = (d >> 22) & 1u, amxTile = (d >> 24) & 1u;
    const bool osxsave = __get_cpuid(1, &a, &b, &c, &d) && ((c >> 27) & 1u);
    if (!amxBf16 || !amxTile || !osxsave || !detectBf16())
        return false;
    unsigned lo = 0, hi = 0;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    if (((lo >> 17) & 3u) != 3u) // XTILECFG and XTILEDATA enabled by the OS
        return false;
#if defined(__linux__)
    // Linux hands the tile data state to a process only when asked (ARCH_REQ_XCOMP_PERM for
    // XFEATURE_XTILEDATA); without it the first tile instruction would kill the process.
    constexpr long kReqXcompPerm = 0x1023, kXfeatureXtiledata = 18;
    return syscall(SYS_arch_prctl, kReqXcompPerm, kXfeatureXtiledata) == 0;
#else
    return false;
#endif
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
        const bool noAmx = env && std::strcmp(env, "avx512") == 0;
        if (emulate)
            return static_cast<int>(Bf16Mode::Emulated);
        return static_cast<int>(!noAmx && cpuHasAmxBf16() ? Bf16Mode::Amx : Bf16Mode::Hardware);
    }() };
    return mode;
}

} // namespace

bool cpuHasAvx512Bf16()
{
    static const bool has = detectBf16();
    return has;
}

bool cpuHasAmxBf16()
{
    static const bool has = detectAmxBf16();
    return has;
}

Bf16Mode activeBf16Mode()
{
    return static_cast<Bf16Mode>(currentBf16().load(std::memory_order_relaxed));
}

void forceBf16Mode(Bf16Mode mode)
{
    if (mode == Bf16Mode::Amx && !cpuHasAmxBf16())
        mode = Bf16Mode::Hardware;
    if (mode == Bf16Mode::Hardware && !cpuHasAvx512Bf16())
        mode = Bf16Mode::Emulated;
    currentBf16().store(static_cast<int>(mode), std::memory_order_relaxed);
}

const char* bf16ModeName(Bf16Mode mode)
{
    return mode == Bf16Mode::Amx ? "amx" : mode == Bf16Mode::Hardware ? "avx512bf16" : "emulated";
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
