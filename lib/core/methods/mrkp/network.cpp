// SPDX-License-Identifier: Apache-2.0
// The MR-KP inference graph (see methods/mrkp/network.h).
#include "methods/mrkp/network.h"

#include "base/exception.h"
#include "methods/mrkp/kernels.h"
#include "nn/pool.h"
#include "nn/scale_fusion.h"

#include <string>

namespace afn::mrkp {

namespace {

constexpr int kPadMultiple = 1 << (kLevels - 1); // every pooling level exact (mrkp.py)

} // namespace

void Network::load(const nn::WeightsArchive& a)
{
    m_loaded = false;
    if (a.meta("format") != "mrkp")
        throwInvalidArgument("invalid or corrupted weights (" + a.source()
            + "): not an MR-KP archive (metadata format=" + a.meta("format", "(none)") + ")");
    m_enc[0].load(a, "enc0", nn::kBaselineInputChannels);
    const int w = m_enc[0].outChannels();
    for (int l = 1; l < kLevels; ++l)
        m_enc[l].load(a, "enc" + std::to_string(l), w, w);
    for (int l = 0; l < kLevels - 1; ++l) {
        m_up[l].load(a, "up" + std::to_string(l), w);
        if (m_up[l].outChannels() != w)
            throwInvalidArgument("invalid or corrupted weights (" + a.source()
                + "): transposed conv widths differ from the encoder's");
        m_dec[l].load(a, "dec" + std::to_string(l), 2 * w, w);
    }
    for (int l = 0; l < kFilterLevels; ++l) {
        m_head[l].load(a, "head" + std::to_string(l), w, kHeadChannels);
        if (m_head[l].kernelSize() != 1)
            throwInvalidArgument(
                "invalid or corrupted weights (" + a.source() + "): heads must be 1x1");
    }
    for (const auto* set : { &m_enc })
        for (const nn::Conv& c : *set)
            if (c.kernelSize() != 3)
                throwInvalidArgument("invalid or corrupted weights (" + a.source()
                    + "): encoder layers must be 3x3");
    for (const nn::Conv& c : m_dec)
        if (c.kernelSize() != 3)
            throwInvalidArgument(
                "invalid or corrupted weights (" + a.source() + "): decoder layers must be 3x3");
    m_loaded = true;
}

long Network::parameters() const
{
    long n = 0;
    auto add = [&](const nn::Conv& c) {
        n += static_cast<long>(c.kernelSize()) * c.kernelSize() * c.inChannels() * c.outChannels()
            + c.outChannels();
    };
    for (const nn::Conv& c : m_enc)
        add(c);
    for (const nn::Conv& c : m_dec)
        add(c);
    for (const nn::Conv& c : m_head)
        add(c);
    for (const nn::ConvTranspose2x2& c : m_up)
        n += 4L * c.inChannels() * c.outChannels() + c.outChannels();
    return n;
}

void Network::run(const nn::BaselineFeatureViews& in, Image& out)
{
    if (!m_loaded)
        throwInvalidOperation("MR-KP: no weights loaded");
    nn::buildBaselineInput(in, kPadMultiple, m_x, m_colorTa, "MR-KP");
    const double full = static_cast<double>(m_x.width()) * m_x.height();
    auto px = [&](int level) { return full / static_cast<double>(1 << (2 * level)); };
    m_flop = 0.0;
    m_enc[0].run(nullptr, m_x, m_e[0], true);
    m_flop += px(0) * m_enc[0].flopPerPixel();
    for (int l = 1; l < kLevels; ++l) {
        nn::down2(m_e[l - 1], m_pooled[l]);
        m_enc[l].run(nullptr, m_pooled[l], m_e[l], true);
        m_flop += px(l) * m_enc[l].flopPerPixel();
    }
    const Image* y = &m_e[kLevels - 1];
    for (int l = kLevels - 2; l >= 0; --l) {
        const int w = m_e[l].channels();
        m_cat[l].resize(m_e[l].width(), m_e[l].height(), 2 * w);
        m_up[l].run(*y, m_cat[l], 0, true);
        nn::copyChannels(m_e[l], m_cat[l], w);
        m_dec[l].run(nullptr, m_cat[l], m_y[l], true);
        m_flop += px(l) * (m_up[l].flopPerPixel() + m_dec[l].flopPerPixel());
        y = &m_y[l];
    }
    // Kernel filtering from the coarsest level up, blending each into the next finer one.
    m_color[0] = m_colorTa;
    for (int l = 1; l < kFilterLevels; ++l)
        nn::down2(m_color[l - 1], m_color[l]);
    for (int l = kFilterLevels - 1; l >= 0; --l) {
        m_head[l].run(nullptr, m_y[l], m_heads[l], false);
        applyKernels(m_color[l], m_heads[l], m_filtered[l]);
        if (l + 1 < kFilterLevels)
            nn::fuseScales(m_filtered[l], m_filtered[l + 1], m_heads[l], kTaps);
        m_flop += px(l) * (m_head[l].flopPerPixel() + kTaps * (2.0 * 3 + 1));
    }
    nn::cropTo(m_filtered[0], in.colorTa->width(), in.colorTa->height(), out);
}

} // namespace afn::mrkp
