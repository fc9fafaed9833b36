// SPDX-License-Identifier: Apache-2.0
// The CPU implementation of AFN's fused heads + softmax + 7x7 filtering + fusion
// (methods/afn/fusion.h), its row kernel cloned per instruction set (cpu/target.h). The scalar
// helpers stay in this file so that they inline into each clone.
#include "methods/afn/fusion.h"

#include "base/parallel.h"
#include "cpu/afn_filter_avx512.h"
#include "cpu/isa.h"
#include "cpu/simd.h"
#include "cpu/target.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

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

/// Softmax and 7x7 filter of pixels x0 .. x0 + n - 1 of row y of `img`, pixel i's logits at
/// logits + i * stride (overwritten by the portable path), its colour to rgb + 3 i: 16 pixels per
/// call on AVX-512 (rows y - 3 .. y + 3 resident in `planar`; `bf16`: the head ran in bf16),
/// otherwise pixel by pixel.
inline __attribute__((always_inline)) void filterRun(float* logits, int stride, int n,
    const Image& img, const cpu::PlanarRows& planar, int x0, int y, float* rgb, bool avx512,
    bool bf16)
{
    if (avx512) {
        for (int i = 0; i < n; i += 16)
            cpu::softmaxApplyRowAvx512(logits + static_cast<std::size_t>(i) * stride, stride,
                std::min(16, n - i), planar, x0 + i, y, rgb + 3 * i, bf16);
        return;
    }
    for (int i = 0; i < n; ++i) {
        float* l = logits + static_cast<std::size_t>(i) * stride;
        softmax49(l);
        applyKernel(img, x0 + i, y, l, rgb + 3 * i);
    }
}

} // namespace

// Rows [y0, y1) of half-resolution blocks, in column chunks of kChunk blocks. Per chunk the heads
// run through nn::Conv::runRows (the engine's conv kernels, that chunk's columns only) into
// thread-local buffers: a half-res row of head1 logits and two full-res rows of headTA logits,
// about 100 KB, which the softmax then reads while they are in the core's cache (whole rows of
// logits are 2 MB at 4K, 4 MB at 8K: the filtering's time per pixel grew 1.2x from 720p to 4K).
// Softmax and filtering fill the chunk's d_1spp and d_TA (AVX-512: 16 pixels per call,
// cpu/afn_filter_avx512.h; otherwise per pixel), and the fusion runs per 2x2 block. Every value is
// the same whatever the chunk width.
AFN_CPU_CLONES void filterAndFuseRows(
    const FusionInputs& in, const FusionOutputs& out, int y0, int y1)
{
    constexpr int kChunk = 128; // half-res columns per chunk
    const Image& d1 = *in.d1;
    const Image& x = *in.x;
    const int wh = d1.width();
    const int s1 = (in.head1->outChannels() + 15) / 16 * 16; // floats per pixel of the buffers
    const int sTa = (in.headTa->outChannels() + 15) / 16 * 16;
    thread_local std::vector<float> rows1, rowsTa, d1Row, dTaRows;
    thread_local cpu::PlanarRows planar1, planarTa;
    rows1.resize(static_cast<std::size_t>(kChunk) * s1);
    rowsTa.resize(static_cast<std::size_t>(4 * kChunk) * sTa);
    d1Row.resize(static_cast<std::size_t>(kChunk) * 3);
    dTaRows.resize(static_cast<std::size_t>(4 * kChunk) * 3);
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    const bool bf16Head1 = in.head1->precision() == nn::Precision::Bf16;
    const bool bf16HeadTa = in.headTa->precision() == nn::Precision::Bf16;
    if (avx512) {
        planar1.reset(*in.color1Half);
        planarTa.reset(*in.colorTa);
    }
    constexpr int r = kKernelSize / 2;
    for (int yh = y0; yh < y1; ++yh) {
        if (avx512) {
            for (int yy = yh - r; yy <= yh + r; ++yy)
                planar1.ensure(yy);
            for (int yy = 2 * yh - r; yy <= 2 * yh + 1 + r; ++yy)
                planarTa.ensure(yy);
        }
        for (int h0 = 0; h0 < wh; h0 += kChunk) {
            const int nh = std::min(kChunk, wh - h0), f0 = 2 * h0, nf = 2 * nh;
            in.head1->runRows(nullptr, d1, yh, yh + 1, rows1.data(), static_cast<long>(nh) * s1, s1,
                false, h0, h0 + nh);
            in.headTa->runRows(&d1, x, 2 * yh, 2 * yh + 2, rowsTa.data(),
                static_cast<long>(nf) * sTa, sTa, false, f0, f0 + nf);
            // Pixel i of full-res row q of the chunk: logits at (q * nf + i) * sTa.
            filterRun(rows1.data(), s1, nh, *in.color1Half, planar1, h0, yh, d1Row.data(), avx512,
                bf16Head1);
            for (int q = 0; q < 2; ++q)
                filterRun(rowsTa.data() + static_cast<std::size_t>(q) * nf * sTa, sTa, nf,
                    *in.colorTa, planarTa, f0, 2 * yh + q,
                    dTaRows.data() + static_cast<std::size_t>(q) * nf * 3, avx512, bf16HeadTa);
            for (int i = 0; i < nh; ++i) {
                const int xh = h0 + i;
                // 1-spp branch at half resolution.
                const float* d1s = d1Row.data() + 3 * i;
                if (out.filtered1Half)
                    std::copy(d1s, d1s + 3, out.filtered1Half->at(xh, yh));
                // TA branch on the four full-resolution pixels of this block.
                const float* dta[4];
                float alpha[4];
                for (int q = 0; q < 4; ++q) {
                    const std::size_t k = static_cast<std::size_t>(q >> 1) * nf + 2 * i + (q & 1);
                    alpha[q]
                        = 1.0f / (1.0f + std::exp(-finiteLogit(rowsTa[k * sTa + kKernelTaps])));
                    dta[q] = dTaRows.data() + k * 3;
                }
                // Eq. 3 on the block; D sums in row order then divides by 4 (as avg_pool2d).
                for (int c = 0; c < 3; ++c) {
                    const float mean = (dta[0][c] + dta[1][c] + dta[2][c] + dta[3][c]) / 4.0f;
                    for (int q = 0; q < 4; ++q) {
                        const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
                        (*out.fused)(px, py, c) = dta[q][c] - alpha[q] * mean + alpha[q] * d1s[c];
                        if (out.filteredTa)
                            (*out.filteredTa)(px, py, c) = dta[q][c];
                    }
                }
                if (out.alpha)
                    for (int q = 0; q < 4; ++q)
                        (*out.alpha)(2 * xh + (q & 1), 2 * yh + (q >> 1), 0) = alpha[q];
            }
        }
    }
}

void filterAndFuse(const FusionInputs& in, const FusionOutputs& out)
{
    const int wh = in.d1->width(), hh = in.d1->height();
    out.fused->resize(2 * wh, 2 * hh, 3);
    out.filteredTa->resize(2 * wh, 2 * hh, 3);
    out.alpha->resize(2 * wh, 2 * hh, 1);
    out.filtered1Half->resize(wh, hh, 3);
    parallelRows(hh, [&](int y0, int y1) { filterAndFuseRows(in, out, y0, y1); });
}

} // namespace afn::afnet
