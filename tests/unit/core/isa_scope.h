// SPDX-License-Identifier: Apache-2.0
// Shared by the tests that compare the AVX-512 kernels with the portable ones: force an instruction
// set for a scope, and ask whether this CPU can run the AVX-512 kernels at all.
#pragma once

#include "cpu/isa.h"

namespace isa_test {

/// cpu::forceIsa(isa) until the end of the scope, then the previous choice again.
struct IsaScope {
    explicit IsaScope(afn::cpu::Isa isa)
        : before(afn::cpu::activeIsa())
    {
        afn::cpu::forceIsa(isa);
    }
    ~IsaScope() { afn::cpu::forceIsa(before); }
    IsaScope(const IsaScope&) = delete;
    IsaScope& operator=(const IsaScope&) = delete;
    afn::cpu::Isa before;
};

/// Whether forcing AVX-512 takes effect (the CPU has AVX-512F and the kernels were built).
inline bool haveAvx512()
{
    IsaScope s(afn::cpu::Isa::Avx512);
    return afn::cpu::activeIsa() == afn::cpu::Isa::Avx512;
}

} // namespace isa_test
