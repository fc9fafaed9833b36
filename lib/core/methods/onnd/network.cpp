// SPDX-License-Identifier: Apache-2.0
// The ONND inference graph (see methods/onnd/network.h).
#include "methods/onnd/network.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "methods/onnd/contrast_gate.h"
#include "nn/pool.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace afn::onnd {

namespace {

constexpr float kLeak = 0.1f;
constexpr float kLogClamp = 20.0f;

void convLeaky(const nn::Conv& conv, const Image* up, const Image& same, Image& out)
{
    conv.run(up, same, out, false);
    nn::leakyRelu(out, kLeak);
}

} // namespace

void Network::load(const nn::WeightsArchive& a)
{
    m_levels.clear();
    if (a.meta("format") != "onnd")
        throwInvalidArgument("invalid or corrupted weights (" + a.source()
            + "): not an ONND archive (metadata format=" + a.meta("format", "(none)") + ")");
    std::vector<Level> levels;
    int cin = nn::kBaselineInputChannels;
    for (int l = 0; a.has("enc" + std::to_string(l) + "a.weight"); ++l) {
        const std::string p = "enc" + std::to_string(l);
        Level lv;
        lv.a.load(a, p + "a", cin);
        const int w = lv.a.outChannels();
        lv.b.load(a, p + "b", 2 * w, w);
        lv.c.load(a, p + "c", w, w);
        cin = w;
        levels.push_back(std::move(lv));
    }
    if (levels.empty() || levels.size() > 6)
        throwInvalidArgument(
            "invalid or corrupted weights (" + a.source() + "): 1 to 6 encoder levels expected");
    m_bott1.load(a, "bott1", cin);
    m_bott2.load(a, "bott2", m_bott1.outChannels(), m_bott1.outChannels());
    int below = m_bott2.outChannels();
    for (int l = static_cast<int>(levels.size()) - 1; l >= 0; --l) {
        const std::string p = "dec" + std::to_string(l);
        const int w = levels[l].a.outChannels();
        levels[l].decA.load(a, p + "a", below + w, w);
        levels[l].decB.load(a, p + "b", w, w);
        below = w;
    }
    m_out.load(a, "out", below, 3);
    for (const Level& lv : levels)
        for (const nn::Conv* c : { &lv.a, &lv.b, &lv.c, &lv.decA, &lv.decB })
            if (c->kernelSize() != 3)
                throwInvalidArgument(
                    "invalid or corrupted weights (" + a.source() + "): layers must be 3x3");
    m_levels = std::move(levels);
    m_hasState = false;
}

long Network::parameters() const
{
    long n = 0;
    auto add = [&](const nn::Conv& c) {
        n += static_cast<long>(c.kernelSize()) * c.kernelSize() * c.inChannels() * c.outChannels()
            + c.outChannels();
    };
    for (const Level& lv : m_levels)
        for (const nn::Conv* c : { &lv.a, &lv.b, &lv.c, &lv.decA, &lv.decB })
            add(*c);
    add(m_bott1);
    add(m_bott2);
    add(m_out);
    return n;
}

void Network::run(const nn::BaselineFeatureViews& in, Image& out)
{
    if (!loaded())
        throwInvalidOperation("ONND: no weights loaded");
    // Padded to a multiple of 2^levels: every pooling level is exact (onnd.py pad_multiple).
    nn::buildBaselineInput(in, 1 << m_levels.size(), m_x, m_colorTa, "ONND");
    const int w = in.colorTa->width(), h = in.colorTa->height();
    // A state of another size (the frame size changed) starts a new history.
    const bool usePrev = m_hasState && m_levels[0].prev.width() == m_x.width()
        && m_levels[0].prev.height() == m_x.height();
    m_flop = 0.0;
    const Image* x = &m_x;
    for (std::size_t l = 0; l < m_levels.size(); ++l) {
        Level& lv = m_levels[l];
        const double px = static_cast<double>(x->width()) * x->height();
        convLeaky(lv.a, nullptr, *x, lv.aOut);
        const int c = lv.aOut.channels();
        lv.cat.resize(x->width(), x->height(), 2 * c);
        if (!usePrev)
            lv.cat.fill(0.0f);
        nn::copyChannels(lv.aOut, lv.cat, 0);
        if (usePrev)
            nn::copyChannels(lv.prev, lv.cat, c);
        convLeaky(lv.b, nullptr, lv.cat, lv.bOut);
        convLeaky(lv.c, nullptr, lv.bOut, lv.h);
        nn::maxPool2(lv.h, lv.pooled);
        x = &lv.pooled;
        m_flop += px * (lv.a.flopPerPixel() + lv.b.flopPerPixel() + lv.c.flopPerPixel());
    }
    const double bottPx = static_cast<double>(x->width()) * x->height();
    convLeaky(m_bott1, nullptr, *x, m_bottMid);
    convLeaky(m_bott2, nullptr, m_bottMid, m_bottOut);
    m_flop += bottPx * (m_bott1.flopPerPixel() + m_bott2.flopPerPixel());
    const Image* y = &m_bottOut;
    for (int l = static_cast<int>(m_levels.size()) - 1; l >= 0; --l) {
        Level& lv = m_levels[l];
        convLeaky(lv.decA, y, lv.h, lv.up);
        convLeaky(lv.decB, nullptr, lv.up, lv.dec);
        y = &lv.dec;
        m_flop += static_cast<double>(lv.h.width()) * lv.h.height()
            * (lv.decA.flopPerPixel() + lv.decB.flopPerPixel());
    }
    m_out.run(nullptr, *y, m_result, false);
    m_flop += static_cast<double>(m_result.width()) * m_result.height() * m_out.flopPerPixel();
    contrastGate(m_colorTa, m_gate);
    m_irr.resize(m_result.width(), m_result.height(), 3);
    parallelRows(m_irr.height(), [&](int y0, int y1) {
        for (int yy = y0; yy < y1; ++yy)
            for (int xx = 0; xx < m_irr.width(); ++xx)
                for (int k = 0; k < 3; ++k) {
                    const float c = std::max(m_colorTa(xx, yy, k), 0.0f);
                    const float logit = std::log1p(c) + m_result(xx, yy, k);
                    const float net = std::exp(std::min(logit, kLogClamp)) - 1.0f;
                    // g == 0 (a flat window) returns c exactly (contrast_gate.h).
                    m_irr(xx, yy, k) = c + m_gate(xx, yy, 0) * (net - c);
                }
    });
    nn::cropTo(m_irr, w, h, out);
    for (Level& lv : m_levels)
        std::swap(lv.prev, lv.h);
    m_hasState = true;
}

} // namespace afn::onnd
