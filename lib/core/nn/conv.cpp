// SPDX-License-Identifier: Apache-2.0
// Direct convolutions of the AFN engine (see afn_conv.h).
#include "nn/conv.h"

#include "cpu/simd.h"
#include "base/exception.h"
#include "base/parallel.h"

#include <algorithm>

// Vector helpers are always inlined within one target clone: the AVX ABI note does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace afn::nn {

namespace {

std::string shapeText(const std::vector<std::int64_t>& d)
{
    std::string s = "(";
    for (std::size_t i = 0; i < d.size(); ++i)
        s += (i ? ", " : "") + std::to_string(d[i]);
    return s + ")";
}

} // namespace

void Conv::load(
    const WeightsArchive& a, const std::string& name, int expectedIn, int expectedOut)
{
    const WeightTensor& w = a.tensor(name + ".weight");
    const WeightTensor& b = a.tensor(name + ".bias");
    auto bad = [&](const std::string& why) {
        throwInvalidArgument("invalid or corrupted weights (" + a.source() + "): '" + name
            + ".weight' " + shapeText(w.dims) + ": " + why);
    };
    if (w.dims.size() != 4 || w.dims[2] != w.dims[3])
        bad("expected (out, in, k, k)");
    const int out = static_cast<int>(w.dims[0]), in = static_cast<int>(w.dims[1]);
    const int k = static_cast<int>(w.dims[2]);
    if (k != 1 && k != 3)
        bad("kernel size must be 1 or 3");
    if (out < 1 || out > kMaxChannels)
        bad("output channels out of range");
    if (in != expectedIn)
        bad("expected " + std::to_string(expectedIn) + " input channels");
    if (expectedOut >= 0 && out != expectedOut)
        bad("expected " + std::to_string(expectedOut) + " output channels");
    if (b.dims.size() != 1 || b.dims[0] != out)
        bad("bias shape " + shapeText(b.dims) + " does not match");
    m_in = in;
    m_out = out;
    m_k = k;
    m_outPadded = (out + 7) / 8 * 8;
    m_bp.assign(m_outPadded, 0.0f);
    std::copy(b.data.begin(), b.data.end(), m_bp.begin());
    m_wp.assign(static_cast<std::size_t>(k) * k * in * m_outPadded, 0.0f);
    for (int co = 0; co < out; ++co)
        for (int ci = 0; ci < in; ++ci)
            for (int t = 0; t < k * k; ++t)
                m_wp[(static_cast<std::size_t>(t) * in + ci) * m_outPadded + co]
                    = w.data[(static_cast<std::size_t>(co) * in + ci) * k * k + t];
}

namespace {

typedef cpu::V8 V8;
typedef cpu::V8u V8u;
constexpr int kLanes = 8;
constexpr int kPixels = 4; // output pixels per micro-kernel call (register blocking)

const float* zeros()
{
    static const float z[kMaxChannels] = {};
    return z;
}

} // namespace

namespace {

struct ConvArgs {
    const Image* up;
    const Image* same;
    Image* out;
    const float* wp; ///< [ky][kx][ci][cp]
    const float* bp; ///< [cp]
    int in, k, cp, outC, nu, ns;
    bool relu;
};

// Rows [y0, y1) of one convolution: 4 output pixels x 8 output channels per micro-kernel step.
// Compiled twice (ifunc dispatch at load time): for x86-64-v3 (AVX2 + FMA) and the baseline.
// Results may differ in the last bit between the two (FMA contraction); parity holds for both.
__attribute__((target_clones("arch=x86-64-v3", "default"))) void convRows(
    const ConvArgs& a, int y0, int y1)
{
    const int w = a.same->width(), h = a.same->height(), r = a.k / 2, cp = a.cp;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; x += kPixels) {
            const int np = std::min(kPixels, w - x);
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
                    float* dst = a.out->at(x + p, y) + cb;
                    for (int o = 0; o < nc; ++o)
                        dst[o] = a.relu ? std::max(acc[p][o], 0.0f) : acc[p][o];
                }
            }
        }
}

} // namespace

void Conv::run(const Image* up, const Image& same, Image& out, bool relu) const
{
    const int w = same.width(), h = same.height();
    const int nu = up ? up->channels() : 0, ns = same.channels();
    if (nu + ns != m_in)
        throwInvalidOperation("AFN conv: input has " + std::to_string(nu + ns) + " channels, layer "
            + "expects " + std::to_string(m_in));
    out.resize(w, h, m_out);
    const ConvArgs args { up, &same, &out, m_wp.data(), m_bp.data(), m_in, m_k, m_outPadded, m_out,
        nu, ns, relu };
    parallelRows(h, [&](int y0, int y1) { convRows(args, y0, y1); });
}

void down2(const Image& in, Image& out)
{
    const int w = in.width() / 2, h = in.height() / 2, c = in.channels();
    out.resize(w, h, c);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* a = in.at(2 * x, 2 * y);
                const float* b = in.at(2 * x + 1, 2 * y);
                const float* cc = in.at(2 * x, 2 * y + 1);
                const float* d = in.at(2 * x + 1, 2 * y + 1);
                float* o = out.at(x, y);
                // PyTorch avg_pool2d sums the window in row order, then divides by 4.
                for (int k = 0; k < c; ++k)
                    o[k] = (a[k] + b[k] + cc[k] + d[k]) / 4.0f;
            }
    });
}

} // namespace afn::nn
