// SPDX-License-Identifier: Apache-2.0
// AFN large (see methods/afn/network_large.h).
#include "methods/afn/network_large.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "methods/afn/fusion.h"
#include "methods/afn/network.h"
#include "nn/scale_fusion.h"

#include <algorithm>
#include <chrono>
#include <string>

namespace afn::afnet {

namespace {

constexpr int kInputChannels = 10; // T(c) 3, albedo 3, normal01 3, depth01 1
constexpr int kRefineChannels = 10; // T(o) 3, albedo 3, normal01 3, depth01 1
constexpr int kLargeKernel = 5;
constexpr int kLargeTaps = kLargeKernel * kLargeKernel;

/// out = per-pixel softmax(logits[0..24]) 5x5 kernels applied to `color` (3 ch), reading it with
/// edge replication outside; the taps are summed in index order (PyTorch's order in
/// model_large.apply_kernels5).
void filterScale(const Image& color, const Image& logits, Image& out)
{
    const int w = color.width(), h = color.height();
    out.resize(w, h, 3);
    constexpr int r = kLargeKernel / 2;
    parallelRows(h, [&](int y0, int y1) {
        float k[kLargeTaps];
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                std::copy(logits.at(x, y), logits.at(x, y) + kLargeTaps, k);
                softmax(k, kLargeTaps);
                float acc[3] = { 0.0f, 0.0f, 0.0f };
                for (int j = 0; j < kLargeTaps; ++j) {
                    const int sy = std::clamp(y + j / kLargeKernel - r, 0, h - 1);
                    const int sx = std::clamp(x + j % kLargeKernel - r, 0, w - 1);
                    const float* c = color.at(sx, sy);
                    for (int ch = 0; ch < 3; ++ch)
                        acc[ch] += k[j] * c[ch];
                }
                std::copy(acc, acc + 3, out.at(x, y));
            }
    });
}

double msSince(std::chrono::steady_clock::time_point t)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

} // namespace

void LargeNetwork::load(const nn::WeightsArchive& a)
{
    m_enc1.load(a, "enc1", kInputChannels);
    m_enc2.load(a, "enc2", m_enc1.outChannels());
    m_enc3.load(a, "enc3", m_enc2.outChannels());
    m_dec2.load(a, "dec2", m_enc3.outChannels() + m_enc2.outChannels());
    m_dec1.load(a, "dec1", m_dec2.outChannels() + m_enc1.outChannels());
    m_head3.load(a, "head3", m_dec2.outChannels(), kLargeTaps);
    m_head2.load(a, "head2", m_dec1.outChannels(), kLargeTaps + 1);
    m_head1.load(a, "head1", m_dec1.outChannels() + kInputChannels, kLargeTaps + 1);
    const char* modules[] = { "refA", "refB" };
    for (int m = 0; m < 2; ++m) {
        const std::string name = modules[m];
        m_ref[3 * m].load(a, name + "1", kRefineChannels);
        m_ref[3 * m + 1].load(a, name + "2", m_ref[3 * m].outChannels());
        m_ref[3 * m + 2].load(a, name + "3", m_ref[3 * m + 1].outChannels(), 3);
    }
    for (const nn::Conv* c : { &m_enc1, &m_enc2, &m_enc3, &m_dec2, &m_dec1 })
        if (c->kernelSize() != 3)
            throwInvalidArgument("invalid or corrupted weights (" + a.source()
                + "): encoder/decoder layers must be 3x3");
    for (const nn::Conv* c : { &m_head1, &m_head2, &m_head3 })
        if (c->kernelSize() != 1)
            throwInvalidArgument(
                "invalid or corrupted weights (" + a.source() + "): heads must be 1x1");
    for (const nn::Conv& c : m_ref)
        if (c.kernelSize() != 3)
            throwInvalidArgument(
                "invalid or corrupted weights (" + a.source() + "): refinement layers must be 3x3");
}

const nn::Conv& LargeNetwork::layer(int index) const
{
    const nn::Conv* layers[kLayers] = { &m_enc1, &m_enc2, &m_enc3, &m_dec2, &m_dec1, &m_head3,
        &m_head2, &m_head1, &m_ref[0], &m_ref[1], &m_ref[2], &m_ref[3], &m_ref[4], &m_ref[5] };
    if (index < 0 || index >= kLayers)
        throwInvalidArgument("AFN large: no layer " + std::to_string(index));
    return *layers[index];
}

void LargeNetwork::prepare(const Inputs& in)
{
    const int w = in.color1->width(), h = in.color1->height();
    m_padW = paddedSize(w);
    m_padH = paddedSize(h);
    m_x.resize(m_padW, m_padH, kInputChannels);
    m_c.resize(m_padW, m_padH, 3);
    parallelRows(m_padH, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int xx = 0; xx < m_padW; ++xx) {
                const int sx = std::min(xx, w - 1), sy = std::min(y, h - 1); // edge replication
                const float* c = in.color1->at(sx, sy);
                float* o = m_x.at(xx, y);
                for (int k = 0; k < 3; ++k) {
                    o[k] = toneMap(c[k]);
                    o[3 + k] = in.albedo->at(sx, sy)[k];
                    o[6 + k] = in.normal01->at(sx, sy)[k];
                    m_c.at(xx, y)[k] = c[k];
                }
                o[9] = in.depth01->at(sx, sy)[0];
            }
    });
    nn::down2(m_c, m_cHalf);
    nn::down2(m_cHalf, m_cQuarter);
}

void LargeNetwork::predict()
{
    nn::down2(m_x, m_xHalf);
    m_enc1.run(nullptr, m_xHalf, m_e1, true);
    nn::down2(m_e1, m_e1Pool);
    m_enc2.run(nullptr, m_e1Pool, m_e2, true);
    nn::down2(m_e2, m_e2Pool);
    m_enc3.run(nullptr, m_e2Pool, m_e3, true);
    m_dec2.run(&m_e3, m_e2, m_d2, true);
    m_dec1.run(&m_d2, m_e1, m_d1, true);
}

void LargeNetwork::filterAndFuse()
{
    m_head3.run(nullptr, m_d2, m_h3, false);
    m_head2.run(nullptr, m_d1, m_h2, false);
    m_head1.run(&m_d1, m_x, m_h1, false);
    filterScale(m_cQuarter, m_h3, m_f3);
    filterScale(m_cHalf, m_h2, m_f2);
    filterScale(m_c, m_h1, m_f1);
    nn::fuseScales(m_f2, m_f3, m_h2, kLargeTaps); // o2, in place
    m_fused = m_f1;
    nn::fuseScales(m_fused, m_f2, m_h1, kLargeTaps); // i
}

void LargeNetwork::refine()
{
    m_o = m_fused;
    m_refIn.resize(m_padW, m_padH, kRefineChannels);
    for (int m = 0; m < 2; ++m) {
        parallelRows(m_padH, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                for (int xx = 0; xx < m_padW; ++xx) {
                    const float* o = m_o.at(xx, y);
                    float* r = m_refIn.at(xx, y);
                    for (int c = 0; c < 3; ++c)
                        r[c] = toneMap(o[c]);
                    std::copy(m_x.at(xx, y) + 3, m_x.at(xx, y) + kInputChannels, r + 3);
                }
        });
        m_ref[3 * m].run(nullptr, m_refIn, m_r1, true);
        m_ref[3 * m + 1].run(nullptr, m_r1, m_r2, true);
        m_ref[3 * m + 2].run(nullptr, m_r2, m_r3, false);
        for (std::size_t k = 0; k < m_o.size(); ++k)
            m_o.data()[k] += m_r3.data()[k];
    }
}

void LargeNetwork::run(const Inputs& in, Image& out, double ms[3])
{
    auto t = std::chrono::steady_clock::now();
    prepare(in);
    predict();
    ms[0] = msSince(t);
    t = std::chrono::steady_clock::now();
    filterAndFuse();
    ms[1] = msSince(t);
    t = std::chrono::steady_clock::now();
    refine();
    const int w = in.color1->width(), h = in.color1->height();
    out.resize(w, h, 3);
    for (int y = 0; y < h; ++y)
        std::copy(m_o.at(0, y), m_o.at(0, y) + 3 * w, out.at(0, y));
    ms[2] = msSince(t);
}

double LargeNetwork::stageFlop(int stage) const
{
    const double full = static_cast<double>(m_padW) * m_padH;
    const double half = full / 4, quarter = full / 16, eighth = full / 64;
    if (stage == 0)
        return m_enc1.flopPerPixel() * half + m_enc2.flopPerPixel() * quarter
            + m_enc3.flopPerPixel() * eighth + m_dec2.flopPerPixel() * quarter
            + m_dec1.flopPerPixel() * half;
    if (stage == 1)
        return m_head3.flopPerPixel() * quarter + m_head2.flopPerPixel() * half
            + m_head1.flopPerPixel() * full + 2.0 * kLargeTaps * 3 * (full + half + quarter);
    double ref = 0.0;
    for (const nn::Conv& c : m_ref)
        ref += c.flopPerPixel();
    return ref * full;
}

} // namespace afn::afnet
