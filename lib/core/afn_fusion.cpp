// SPDX-License-Identifier: Apache-2.0
// Fused heads + softmax + 7x7 filtering + fusion of AFN (see afn_fusion.h).
#include "afn_fusion.h"

#include "parallel.h"

#include <algorithm>
#include <cmath>

namespace afn {

void afnSoftmax(float* v, int n)
{
    float m = v[0];
    for (int j = 1; j < n; ++j) m = std::max(m, v[j]);
    float s = 0.0f;
    for (int j = 0; j < n; ++j) {
        v[j] = std::exp(v[j] - m);
        s += v[j];
    }
    const float inv = 1.0f / s;
    for (int j = 0; j < n; ++j) v[j] *= inv;
}

void afnApplyKernel(const Image& img, int x, int y, const float* k, float* rgb)
{
    constexpr int r = kAfnKernelSize / 2;
    const int w = img.width(), h = img.height();
    float a0 = 0.0f, a1 = 0.0f, a2 = 0.0f;
    if (x >= r && y >= r && x + r < w && y + r < h) {
        for (int dy = 0; dy < kAfnKernelSize; ++dy) {
            const float* p = img.at(x - r, y + dy - r);
            const float* kk = k + dy * kAfnKernelSize;
            for (int dx = 0; dx < kAfnKernelSize; ++dx, p += 3) {
                a0 += kk[dx] * p[0];
                a1 += kk[dx] * p[1];
                a2 += kk[dx] * p[2];
            }
        }
    } else {
        for (int dy = 0; dy < kAfnKernelSize; ++dy) {
            const int yy = y + dy - r;
            if (yy < 0 || yy >= h) continue;
            for (int dx = 0; dx < kAfnKernelSize; ++dx) {
                const int xx = x + dx - r;
                if (xx < 0 || xx >= w) continue;
                const float* p = img.at(xx, yy);
                const float kv = k[dy * kAfnKernelSize + dx];
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

void afnFilterAndFuse(const AfnFusionInputs& in, const AfnFusionOutputs& out)
{
    const Image& d1 = *in.d1;
    const Image& x = *in.x;
    const int wh = d1.width(), hh = d1.height();
    const int w = 2 * wh, h = 2 * hh;
    out.fused->resize(w, h, 3);
    out.filteredTa->resize(w, h, 3);
    out.alpha->resize(w, h, 1);
    out.filtered1Half->resize(wh, hh, 3);
    const int cd = d1.channels(), cx = x.channels();
    parallelRows(hh, [&](int y0, int y1) {
        float logits[kAfnMaxChannels];
        for (int yh = y0; yh < y1; ++yh)
            for (int xh = 0; xh < wh; ++xh) {
                const float* feat = d1.at(xh, yh);
                // 1-spp branch at half resolution.
                in.head1->evalPixel(feat, cd, nullptr, 0, logits);
                afnSoftmax(logits, kAfnKernelTaps);
                float* d1s = out.filtered1Half->at(xh, yh);
                afnApplyKernel(*in.color1Half, xh, yh, logits, d1s);
                // TA branch on the four full-resolution pixels of this block.
                float dta[4][3], alpha[4];
                for (int q = 0; q < 4; ++q) {
                    const int px = 2 * xh + (q & 1), py = 2 * yh + (q >> 1);
                    in.headTa->evalPixel(feat, cd, x.at(px, py), cx, logits);
                    alpha[q] = 1.0f / (1.0f + std::exp(-logits[kAfnKernelTaps]));
                    afnSoftmax(logits, kAfnKernelTaps);
                    afnApplyKernel(*in.colorTa, px, py, logits, dta[q]);
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
                for (int q = 0; q < 4; ++q) (*out.alpha)(2 * xh + (q & 1), 2 * yh + (q >> 1), 0) = alpha[q];
            }
    });
}

} // namespace afn
