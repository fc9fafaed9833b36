// SPDX-License-Identifier: Apache-2.0
#include "methods/wskpn/network.h"

#include "base/exception.h"
#include "methods/wskpn/weight_sharing_filter.h"
#include "nn/baseline_input.h"
#include "nn/pool.h"

#include <string>

namespace afn::wskpn {

void Network::load(const nn::WeightsArchive& a)
{
    if (a.meta("format") != "wskpn")
        throwInvalidArgument("invalid or corrupted weights (" + a.source()
            + "): not a WSKPN archive (format '" + a.meta("format") + "', expected 'wskpn')");
    std::array<nn::Conv, kLayers> layers;
    int in = nn::kBaselineInputChannels;
    for (int i = 0; i < kLayers; ++i) {
        const std::string name = "conv" + std::to_string(i + 1);
        layers[i].load(a, name, in, i == kLayers - 1 ? kHeadChannels : -1);
        if (layers[i].kernelSize() != 5)
            throwInvalidArgument("invalid or corrupted weights (" + a.source() + "): '" + name
                + ".weight' must be 5x5 (the folded RepVGG block)");
        in = layers[i].outChannels();
    }
    m_layers = std::move(layers); // only a fully valid archive replaces the network
}

double Network::flopPerPixel() const
{
    double f = 0;
    for (const nn::Conv& c : m_layers)
        f += c.flopPerPixel();
    return f;
}

void Network::run(const Image& input, const Image& cta, Image& out)
{
    const Image* x = &input;
    for (int i = 0; i < kLayers; ++i) {
        Image& y = i == kLayers - 1 ? m_head : (i % 2 ? m_b : m_a);
        m_layers[i].run(nullptr, *x, y, false);
        if (i < kLayers - 1)
            nn::leakyRelu(y, kLeakySlope);
        x = &y;
    }
    weightSharingFilter(cta, m_head, m_products, m_sums, out);
}

} // namespace afn::wskpn
