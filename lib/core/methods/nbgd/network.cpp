// SPDX-License-Identifier: Apache-2.0
#include "methods/nbgd/network.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "nn/baseline_input.h"
#include "nn/pool.h"

#include <cmath>

namespace afn::nbgd {

void Network::load(const nn::WeightsArchive& a)
{
    if (a.meta("format") != "nbgd")
        throwInvalidArgument("invalid or corrupted weights (" + a.source()
            + "): not an NBGD archive (format '" + a.meta("format") + "', expected 'nbgd')");
    nn::Conv g1, g2;
    g1.load(a, "guide1", nn::kBaselineInputChannels);
    g2.load(a, "guide2", g1.outChannels(), kGuideOutputs);
    if (g1.kernelSize() != 5 || g2.kernelSize() != 5)
        throwInvalidArgument("invalid or corrupted weights (" + a.source()
            + "): the guide convolutions must be 5x5");
    m_guide1 = std::move(g1); // only a fully valid archive replaces the network
    m_guide2 = std::move(g2);
}

void Network::run(const Image& input, const Image& cta, Image& out)
{
    m_guide1.run(nullptr, input, m_hidden, false);
    nn::leakyRelu(m_hidden, kLeakySlope);
    m_guide2.run(nullptr, m_hidden, m_guides, false);
    // The sigmoid of the guides (every pixel of the network's padded frame), then the guides in
    // [0, 255] for the grids (channels 0-2), as the training code's s * 255; per value, in
    // parallel over rows.
    const std::size_t rowValues = static_cast<std::size_t>(m_guides.width()) * m_guides.channels();
    parallelRows(m_guides.height(), [&](int y0, int y1) {
        float* s = m_guides.at(0, y0);
        for (std::size_t k = 0; k < static_cast<std::size_t>(y1 - y0) * rowValues; ++k)
            s[k] = 1.0f / (1.0f + std::exp(-s[k]));
    });
    m_scaled.resize(cta.width(), cta.height(), kGrids);
    parallelRows(cta.height(), [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < cta.width(); ++x)
                for (int k = 0; k < kGrids; ++k)
                    m_scaled(x, y, k) = m_guides(x, y, k) * kGuideScale;
    });
    parallelFor(kGrids, [&](int k) {
        m_grids[k].filter(cta, m_scaled, k, kGridSteps[k][0], kGridSteps[k][1], m_sliced[k]);
    });
    out.resize(cta.width(), cta.height(), 3);
    parallelRows(cta.height(), [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < cta.width(); ++x) {
                const float w1 = m_guides(x, y, 3), w2 = m_guides(x, y, 4);
                for (int c = 0; c < 3; ++c)
                    out(x, y, c) = w1 * m_sliced[0](x, y, c) + w2 * m_sliced[1](x, y, c)
                        + (1.0f - w1 - w2) * m_sliced[2](x, y, c);
            }
    });
}

} // namespace afn::nbgd
