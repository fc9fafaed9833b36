// SPDX-License-Identifier: Apache-2.0
// The AFN input tone map, scalar (methods/afn/tone_map.h), and the dispatch of toneMapRun.
#include "methods/afn/tone_map.h"

#include "cpu/isa.h"
#include "methods/afn/tone_map_avx512.h"
#include "methods/afn/tone_map_poly.h"

#include <cmath>

namespace afn::afnet {

float toneMap(float x)
{
    using namespace tonemap;
    if (!(x > 0.0f)) // also NaN
        return 0.0f;
    if (x >= 1.0f)
        return 1.0f;
    int e = 0;
    float m = std::frexp(x, &e) * 2.0f; // [1, 2), exact
    e -= 1;
    if (m >= kSqrt2) {
        m = m * 0.5f;
        e += 1;
    }
    const int q = e >= 0 ? e / 11 : -((-e + 10) / 11); // floor(e / 11)
    const int j = e - 11 * q;
    const float s = (m - 1.0f) / (m + 1.0f);
    const float s2 = s * s;
    const float lnm
        = (2.0f * s) * (1.0f + s2 * (kLogC3 + s2 * (kLogC5 + s2 * (kLogC7 + s2 * kLogC9))));
    const float u = lnm * kInvGamma;
    const float p = 1.0f
        + u * (1.0f + u * (kExpC2 + u * (kExpC3 + u * (kExpC4 + u * (kExpC5 + u * kExpC6)))));
    return std::ldexp(kPow2Fifths[j] * p, 5 * q);
}

namespace {

/// The AVX-512 run where the CPU has it (it returns how many values it did), toneMap for the rest.
void runWith(int (*avx512)(const float*, float*, int), const float* in, float* out, int n)
{
    int i = cpu::activeIsa() == cpu::Isa::Avx512 ? avx512(in, out, n) : 0;
    for (; i < n; ++i)
        out[i] = toneMap(in[i]);
}

} // namespace

void toneMapRun(const float* in, float* out, int n)
{
    runWith(toneMapRunAvx512, in, out, n);
}

void toneMapRunBf16(const float* in, float* out, int n)
{
    runWith(toneMapRunAvx512Bf16, in, out, n);
}

} // namespace afn::afnet
