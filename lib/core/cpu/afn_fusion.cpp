// SPDX-License-Identifier: Apache-2.0
// The CPU implementation of AFN's fused heads + softmax + 7x7 filtering + fusion
// (methods/afn/fusion.h), its row kernel cloned per instruction set (cpu/target.h). The scalar
// helpers stay in this file so that they inline into each clone.
#include "methods/afn/fusion.h"

#include "base/parallel.h"
#include "cpu/simd.h"
#include "cpu/target.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

// Vector helpers are always inlined within one target clone: the AVX ABI note does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::afnet {

namespace {

/// A logit that overflowed (+-Inf) becomes +-FLT_MAX and a NaN one (Inf - Inf in a head) the lowest
/// value, so that the softmax stays a distribution (the largest logits share the weight) and the
/// sigmoid a weight in [0, 1]. Finite logits are unchanged.
inline __attribute__((always_inline)) float finiteLogit(float v)
{
    return v != v ? -FLT_MAX : std::min(std::max(v, -FLT_MAX), FLT_MAX);
}

} // namespace

void softmax(float* v, int n)
{
    for (int j = 0; j < n; ++j)
        v[j] = finiteLogit(v[j]);
    float m = v[0];
    for (int j = 1; j < n; ++j)
        m = std::max(m, v[j]);
    float s = 0.0f;
    for (int j = 0; j < n; ++j) {
        v[j] = std::exp(v[j] - m);
        s += v[j];
    }
    const float inv = 1.0f / s;
    for (int j = 0; j < n; ++j)
        v[j] *= inv;
}

void applyKernel(const Image& img, int x, int y, const float* k, float* rgb)
{
    constexpr int r = kKernelSize / 2;
    const int w = img.width(), h = img.height();
    float a0 = 0.0f, a1 = 0.0f, a2 = 0.0f;
    if (x >= r && y >= r && x + r < w && y + r < h) {
        for (int dy = 0; dy < kKernelSize; ++dy) {
            const float* p = img.at(x - r, y + dy - r);
            const float* kk = k + dy * kKernelSize;
            for (int dx = 0; dx < kKernelSize; ++dx, p += 3) {
                a0 += kk[dx] * p[0];
                a1 += kk[dx] * p[1];
                a2 += kk[dx] * p[2];
            }
        }
    } else {
        for (int dy = 0; dy < kKernelSize; ++dy) {
            const int yy = y + dy - r;
            if (yy < 0 || yy >= h)
                continue;
            for (int dx = 0; dx < kKernelSize; ++dx) {
                const int xx = x + dx - r;
                if (xx < 0 || xx >= w)
                    continue;
                const float* p = img.at(xx, yy);
                const float kv = k[dy * kKernelSize + dx];
                a0 += kv * p[0];
                a1 += kv * p[1];
                a2 += kv * p[2];
            }
        }
    }
    rgb[0] = a0;
    rgb[1] = a1;
    rgb[2] = a2;
}

namespace {

// 1x1 head on one pixel with 8-wide vectors: acc[0..cp) = bias + W * concat(a, b).
inline __attribute__((always_inline)) void head1x1(
    const nn::Conv& conv, const float* a, int na, const float* b, int nb, float* acc)
{
    const int cp = conv.paddedOutChannels();
    const float* wt = conv.paddedWeights();
    cpu::V8 v[nn::kMaxChannels / 8];
    const int nv = cp / 8;
    for (int j = 0; j < nv; ++j)
        v[j] = cpu::load8(conv.paddedBias() + 8 * j);
    for (int ci = 0; ci < na; ++ci, wt += cp)
        for (int j = 0; j < nv; ++j)
            v[j] += a[ci] * cpu::load8(wt + 8 * j);
    for (int ci = 0; ci < nb; ++ci, wt += cp)
        for (int j = 0; j < nv; ++j)
            v[j] += b[ci] * cpu::load8(wt + 8 * j);
    for (int j = 0; j < nv; ++j)
        cpu::store8(acc + 8 * j, v[j]);
}

// Softmax over the 49 taps: 6 vectors of 8 plus one scalar tap.
inline __attribute__((always_inline)) void softmax49(float* l)
{
    for (int j = 0; j < kKernelTaps; ++j)
        l[j] = finiteLogit(l[j]);
    float m = l[0];
    for (int j = 1; j < kKernelTaps; ++j)
        m = std::max(m, l[j]);
    const cpu::V8 mv = cpu::splat8(m);
    cpu::V8 sv = cpu::splat8(0.0f);
    for (int j = 0; j < 48; j += 8) {
        const cpu::V8 e = cpu::exp8(cpu::load8(l + j) - mv);
        cpu::store8(l + j, e);
        sv += e;
    }
    l[48] = std::exp(l[48] - m);
    const float s = sv[0] + sv[1] + sv[2] + sv[3] + sv[4] + sv[5] + sv[6] + sv[7] + l[48];
    const float inv = 1.0f / s;
    for (int j = 0; j < kKernelTaps; ++j)
        l[j] *= inv;
}

// Rows [y0, y1) of half-resolution blocks.
AFN_CPU_CLONES void fuseRows(const FusionInputs& in, const FusionOutputs& out, int y0, int y1)
{
    const Image& d1 = *in.d1;
    const Image& x = *in.x;
    const int wh = d1.width(), cd = d1.channels(), cx = x.channels();
    alignas(32) float logits[nn::kMaxChannels];
    for (int yh = y0; yh < y1; ++yh)
        for (int xh = 0; xh < wh; ++xh) {
            const float* feat = d1.at(xh, yh);
            // 1-spp branch at half resolution.
            head1x1(*in.head1, feat, cd, nullptr, 0, logits);
            softmax49(logits);
            float* d1s = out.filtered1Half->at(xh, yh);
            applyKernel(*in.color1Half, xh, yh, logits, d1s);
            // TA branch on the four full-resolution pixels of this block.
            float dta[4][3], alpha[4];
            for (int q = 0; q < 4; ++q) {
                const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
                head1x1(*in.headTa, feat, cd, x.at(px, py), cx, logits);
                alpha[q] = 1.0f / (1.0f + std::exp(-finiteLogit(logits[kKernelTaps])));
                softmax49(logits);
                applyKernel(*in.colorTa, px, py, logits, dta[q]);
            }
            // Eq. 3 on the block; D sums in row order then divides by 4 (as avg_pool2d).
            for (int c = 0; c < 3; ++c) {
                const float mean = (dta[0][c] + dta[1][c] + dta[2][c] + dta[3][c]) / 4.0f;
                for (int q = 0; q < 4; ++q) {
                    const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
                    (*out.fused)(px, py, c) = dta[q][c] - alpha[q] * mean + alpha[q] * d1s[c];
                    (*out.filteredTa)(px, py, c) = dta[q][c];
                }
            }
            for (int q = 0; q < 4; ++q)
                (*out.alpha)(2 * xh + (q & 1), 2 * yh + (q >> 1), 0) = alpha[q];
        }
}

} // namespace

void filterAndFuse(const FusionInputs& in, const FusionOutputs& out)
{
    const int wh = in.d1->width(), hh = in.d1->height();
    out.fused->resize(2 * wh, 2 * hh, 3);
    out.filteredTa->resize(2 * wh, 2 * hh, 3);
    out.alpha->resize(2 * wh, 2 * hh, 1);
    out.filtered1Half->resize(wh, hh, 3);
    parallelRows(hh, [&](int y0, int y1) { fuseRows(in, out, y0, y1); });
}

} // namespace afn::afnet
