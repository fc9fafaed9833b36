// SPDX-License-Identifier: Apache-2.0
// The convolution kernel of nn::Conv (see cpu/conv_kernel.h), cloned per instruction set.
#include "cpu/conv_kernel.h"

#include "cpu/simd.h"
#include "cpu/target.h"
#include "nn/conv.h"

#include <algorithm>

// Vector helpers are always inlined within one target clone: the AVX ABI note does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::cpu {

namespace {

constexpr int kLanes = 8;
constexpr int kPixels = 4; // output pixels per micro-kernel call (register blocking)

const float* zeros()
{
    static const float z[nn::kMaxChannels] = {};
    return z;
}

} // namespace

AFN_CPU_CLONES void convRows(const ConvArgs& a, int y0, int y1)
{
    const int w = a.same->width(), h = a.same->height(), r = a.k / 2, cp = a.cp;
    const int xEnd = columnEnd(a);
    for (int y = y0; y < y1; ++y)
        for (int x = a.x0; x < xEnd; x += kPixels) {
            const int np = std::min(kPixels, xEnd - x);
            for (int cb = 0; cb < cp; cb += kLanes) {
                V8 acc[kPixels];
                const V8 bias = *reinterpret_cast<const V8u*>(a.bp + cb);
                for (int p = 0; p < kPixels; ++p)
                    acc[p] = bias;
                for (int ky = 0; ky < a.k; ++ky) {
                    const int yy = y + ky - r;
                    if (yy < 0 || yy >= h)
                        continue;
                    for (int kx = 0; kx < a.k; ++kx) {
                        const float* wt
                            = a.wp + static_cast<std::size_t>(ky * a.k + kx) * a.in * cp + cb;
                        const float* pu[kPixels];
                        const float* ps[kPixels];
                        for (int p = 0; p < kPixels; ++p) {
                            const int xx = x + p + kx - r;
                            const bool in = p < np && xx >= 0 && xx < w;
                            pu[p] = in && a.nu ? a.up->at(xx >> 1, yy >> 1) : zeros();
                            ps[p] = in ? a.same->at(xx, yy) : zeros();
                        }
                        for (int ci = 0; ci < a.nu; ++ci, wt += cp) {
                            const V8 wv = *reinterpret_cast<const V8u*>(wt);
                            for (int p = 0; p < kPixels; ++p)
                                acc[p] += pu[p][ci] * wv;
                        }
                        for (int ci = 0; ci < a.ns; ++ci, wt += cp) {
                            const V8 wv = *reinterpret_cast<const V8u*>(wt);
                            for (int p = 0; p < kPixels; ++p)
                                acc[p] += ps[p][ci] * wv;
                        }
                    }
                }
                const int nc = std::min(kLanes, a.outC - cb);
                for (int p = 0; p < np; ++p) {
                    float* dst = a.dst + (y - a.dstY0) * a.dstRow
                        + static_cast<long>(x - a.x0 + p) * a.dstPix + cb;
                    for (int o = 0; o < nc; ++o)
                        dst[o] = a.relu ? std::max(acc[p][o], 0.0f) : acc[p][o];
                }
            }
        }
}

} // namespace afn::cpu
