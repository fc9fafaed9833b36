// SPDX-License-Identifier: Apache-2.0
// Direct convolutions of the AFN engine (see nn/conv.h).
#include "nn/conv.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "cpu/bf16.h"
#include "cpu/conv_kernel.h"
#include "cpu/isa.h"

#include <algorithm>

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

void Conv::load(const WeightsArchive& a, const std::string& name, int expectedIn, int expectedOut)
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
    if (k != 1 && k != 3 && k != 5)
        bad("kernel size must be 1, 3 or 5");
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
    m_outPadded16 = (out + 15) / 16 * 16;
    m_bp16.assign(m_outPadded16, 0.0f);
    std::copy(b.data.begin(), b.data.end(), m_bp16.begin());
    m_wp16.assign(static_cast<std::size_t>(k) * k * in * m_outPadded16, 0.0f);
    for (std::size_t row = 0; row < static_cast<std::size_t>(k) * k * in; ++row)
        std::copy_n(&m_wp[row * m_outPadded], out, &m_wp16[row * m_outPadded16]);
    m_wt16.clear();
    m_wbf16.clear();
    m_wtbf16.clear();
    m_wamx.clear();
    m_precision = Precision::Fp32;
    if (out > cpu::kFewOutputs) {
        const int pairs = (in + 1) / 2;
        m_wbf16.assign(static_cast<std::size_t>(k) * k * pairs * m_outPadded16 * 2, 0);
        for (int t = 0; t < k * k; ++t)
            for (int ci = 0; ci < in; ++ci)
                for (int co = 0; co < out; ++co)
                    m_wbf16[((static_cast<std::size_t>(t) * pairs + ci / 2) * m_outPadded16 + co)
                            * 2
                        + (ci & 1)]
                        = cpu::toBf16(w.data[(static_cast<std::size_t>(co) * in + ci) * k * k + t]);
        if (cpu::cpuHasAmxBf16()) {
            // cpu/conv_amx_bf16.h: each tap's pairs padded with zero pairs to c / 2, c = the
            // input channels rounded up to 16, so that every chunk of the band is a whole tile.
            const std::size_t rowPairs = static_cast<std::size_t>(m_outPadded16) * 2;
            const int padded = cpu::bandChannels(in) / 2;
            m_wamx.assign(static_cast<std::size_t>(k) * k * padded * rowPairs + 32, 0);
            const auto base = reinterpret_cast<std::uintptr_t>(m_wamx.data());
            m_wamxOffset = ((64 - base % 64) % 64) / sizeof(std::uint16_t);
            for (int t = 0; t < k * k; ++t)
                std::copy_n(&m_wbf16[static_cast<std::size_t>(t) * pairs * rowPairs],
                    pairs * rowPairs,
                    &m_wamx[m_wamxOffset + static_cast<std::size_t>(t) * padded * rowPairs]);
        }
    }
    if (out <= cpu::kFewOutputs) {
        const int inPadded = cpu::bandChannels(in);
        m_wt16.assign(static_cast<std::size_t>(k) * k * out * inPadded, 0.0f);
        for (int t = 0; t < k * k; ++t)
            for (int co = 0; co < out; ++co)
                for (int ci = 0; ci < in; ++ci)
                    m_wt16[(static_cast<std::size_t>(t) * out + co) * inPadded + ci]
                        = w.data[(static_cast<std::size_t>(co) * in + ci) * k * k + t];
        const int chunks = cpu::fewOutputsChunks(k, in);
        m_wtbf16.assign(static_cast<std::size_t>(k) * out * chunks * 32, 0);
        for (int ky = 0; ky < k; ++ky)
            for (int co = 0; co < out; ++co)
                for (int kx = 0; kx < k; ++kx)
                    for (int ci = 0; ci < in; ++ci)
                        m_wtbf16[(static_cast<std::size_t>(ky) * out + co) * chunks * 32
                            + static_cast<std::size_t>(kx) * inPadded + ci]
                            = cpu::toBf16(w.data[(static_cast<std::size_t>(co) * in + ci) * k * k
                                + ky * k + kx]);
    }
}

cpu::ConvArgs Conv::args(const Image* up, const Image& same, bool relu) const
{
    const int nu = up ? up->channels() : 0, ns = same.channels();
    if (nu + ns != m_in)
        throwInvalidOperation("AFN conv: input has " + std::to_string(nu + ns) + " channels, layer "
            + "expects " + std::to_string(m_in));
    cpu::ConvArgs a { up, &same, m_wp.data(), m_bp.data(), m_in, m_k, m_outPadded, m_out, nu, ns,
        relu };
    a.wp16 = m_wp16.data();
    a.bp16 = m_bp16.data();
    a.cp16 = m_outPadded16;
    a.wt16 = m_wt16.empty() ? nullptr : m_wt16.data();
    if (precision() == Precision::Bf16) {
        a.wbf16 = m_wbf16.empty() ? nullptr : m_wbf16.data();
        a.wtbf16 = m_wtbf16.empty() ? nullptr : m_wtbf16.data();
    }
    if (precision() == Precision::Bf16 && !m_wamx.empty())
        a.wamx = m_wamx.data() + m_wamxOffset;
    return a;
}

void Conv::run(const Image* up, const Image& same, Image& out, bool relu) const
{
    const int w = same.width(), h = same.height();
    cpu::ConvArgs a = args(up, same, relu);
    out.resize(w, h, m_out);
    a.dst = out.data();
    a.dstRow = static_cast<long>(w) * m_out;
    a.dstPix = m_out;
    if (cpu::activeIsa() == cpu::Isa::Avx512)
        parallelRows(h, [&](int y0, int y1) { cpu::convRowsAvx512(a, y0, y1); });
    else
        parallelRows(h, [&](int y0, int y1) { cpu::convRows(a, y0, y1); });
}

void Conv::runRows(const Image* up, const Image& same, int y0, int y1, float* dst, long rowStride,
    int pixelStride, bool relu, int x0, int x1) const
{
    cpu::ConvArgs a = args(up, same, relu);
    a.x0 = x0;
    a.x1 = x1;
    a.dst = dst;
    a.dstRow = rowStride;
    a.dstPix = pixelStride;
    a.dstY0 = y0;
    if (cpu::activeIsa() == cpu::Isa::Avx512)
        cpu::convRowsAvx512(a, y0, y1);
    else
        cpu::convRows(a, y0, y1);
}

void down2Rows(const Image& in, Image& out, int y0, int y1)
{
    const int w = out.width(), c = in.channels();
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
}

void down2(const Image& in, Image& out)
{
    out.resize(in.width() / 2, in.height() / 2, in.channels());
    parallelRows(out.height(), [&](int y0, int y1) { down2Rows(in, out, y0, y1); });
}

} // namespace afn::nn
