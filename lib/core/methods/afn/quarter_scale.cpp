// SPDX-License-Identifier: Apache-2.0
#include "methods/afn/quarter_scale.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "methods/afn/fusion.h"

#include <algorithm>
#include <cmath>

namespace afn::afnet {

namespace {

/// PyTorch's bilinear source index (align_corners=False, scale 1/4): first tap, second tap and
/// the second tap's weight.
struct Taps {
    int i0, i1;
    float l1;
};

Taps sourceTaps(int dst, int srcSize)
{
    float s = 0.25f * (static_cast<float>(dst) + 0.5f) - 0.5f;
    s = std::max(s, 0.0f);
    const int i0 = std::min(static_cast<int>(s), srcSize - 1);
    const int i1 = i0 + (i0 < srcSize - 1 ? 1 : 0);
    return { i0, i1, s - static_cast<float>(i0) };
}

} // namespace

void addUpsampled4(const Image& src, Image& dst)
{
    const int w = dst.width(), h = dst.height(), ws = src.width(), hs = src.height();
    if (src.channels() != 3 || dst.channels() != 3 || ws * 4 != w || hs * 4 != h)
        throwInvalidArgument("AFN quarter scale: sizes do not match (4x upsampling)");
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const Taps ty = sourceTaps(y, hs);
            const float h1 = ty.l1, h0 = 1.0f - h1;
            for (int x = 0; x < w; ++x) {
                const Taps tx = sourceTaps(x, ws);
                const float w1 = tx.l1, w0 = 1.0f - w1;
                const float* a = src.at(tx.i0, ty.i0);
                const float* b = src.at(tx.i1, ty.i0);
                const float* c = src.at(tx.i0, ty.i1);
                const float* d = src.at(tx.i1, ty.i1);
                float* o = dst.at(x, y);
                for (int ch = 0; ch < 3; ++ch)
                    o[ch] += h0 * (w0 * a[ch] + w1 * b[ch]) + h1 * (w0 * c[ch] + w1 * d[ch]);
            }
        }
    });
}

void applyQuarterScale(const nn::Conv& head4, const Image& d2, Image& fused, QuarterBuffers& buf)
{
    nn::down2(fused, buf.half);
    nn::down2(buf.half, buf.low);
    const int wq = buf.low.width(), hq = buf.low.height();
    if (d2.width() != wq || d2.height() != hq)
        throwInvalidArgument("AFN quarter scale: d2 is not at a quarter of the fused image");
    head4.run(nullptr, d2, buf.logits, false);
    buf.delta.resize(wq, hq, 3);
    parallelRows(hq, [&](int y0, int y1) {
        float k[kKernelTaps], rgb[3];
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < wq; ++x) {
                const float* q = buf.logits.at(x, y);
                std::copy(q, q + kKernelTaps, k);
                softmax(k, kKernelTaps);
                applyKernel(buf.low, x, y, k, rgb);
                const float beta = 1.0f / (1.0f + std::exp(-q[kKernelTaps]));
                const float* l = buf.low.at(x, y);
                float* o = buf.delta.at(x, y);
                for (int c = 0; c < 3; ++c)
                    o[c] = beta * (rgb[c] - l[c]);
            }
    });
    addUpsampled4(buf.delta, fused);
}

} // namespace afn::afnet
