// SPDX-License-Identifier: Apache-2.0
// AFN large's graph on the CPU (see emulated_large.h), in cuda/large_graph.cpp's order.
#include "emulated_large.h"

#include <cmath>

namespace afntest {

using namespace afn::cuda;

void EmulatedLargeGraph::setNetwork(const afn::afnet::LargeNetwork& net)
{
    for (int i = 0; i < afn::afnet::LargeNetwork::kLayers; ++i) {
        int up = 0;
        if (i == static_cast<int>(L::Dec2))
            up = net.layer(static_cast<int>(L::Enc3)).outChannels();
        else if (i == static_cast<int>(L::Dec1))
            up = net.layer(static_cast<int>(L::Dec2)).outChannels();
        else if (i == static_cast<int>(L::Head1))
            up = net.layer(static_cast<int>(L::Dec1)).outChannels();
        m_layers[i].packed = packConv(net.layer(i), up);
    }
}

void EmulatedLargeGraph::allocate(int wp, int hp)
{
    if (wp == m_paddedWidth && hp == m_paddedHeight)
        return;
    const auto channels = [&](L l, int offset = 0) { return layer(l, offset).packed.outChannels; };
    m_x.allocate(wp, hp, kLargeInputChannels);
    m_xHalf.allocate(wp / 2, hp / 2, kLargeInputChannels);
    m_e1.allocate(wp / 2, hp / 2, channels(L::Enc1));
    m_e1Pool.allocate(wp / 4, hp / 4, channels(L::Enc1));
    m_e2.allocate(wp / 4, hp / 4, channels(L::Enc2));
    m_e2Pool.allocate(wp / 8, hp / 8, channels(L::Enc2));
    m_e3.allocate(wp / 8, hp / 8, channels(L::Enc3));
    m_d2.allocate(wp / 4, hp / 4, channels(L::Dec2));
    m_d1.allocate(wp / 2, hp / 2, channels(L::Dec1));
    const std::size_t full = static_cast<std::size_t>(wp) * hp, half = full / 4;
    const std::size_t quarter = full / 16;
    const float nan = std::nanf("");
    m_c.assign(3 * full, nan);
    m_cHalf.assign(3 * half, nan);
    m_cQuarter.assign(3 * quarter, nan);
    m_h1.assign(channels(L::Head1) * full, nan);
    m_h2.assign(channels(L::Head2) * half, nan);
    m_h3.assign(channels(L::Head3) * quarter, nan);
    m_f2.assign(3 * half, nan);
    m_f3.assign(3 * quarter, nan);
    m_fused.assign(3 * full, nan);
    m_refined.assign(3 * full, nan);
    m_refineInput.allocate(wp, hp, kLargeInputChannels);
    m_r1.allocate(wp, hp, channels(L::RefA1));
    m_r2.allocate(wp, hp, channels(L::RefA1, 1));
    m_paddedWidth = wp;
    m_paddedHeight = hp;
}

void EmulatedLargeGraph::run(const LargeSources& src, const FinalOutput& out)
{
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    // Prepare.
    emulateLargePrepare(largePrepareBuffers(
        src, wp, hp, m_x.data.data(), m_xHalf.data.data(), m_c.data(), m_cHalf.data()));
    emulateDown2(m_cHalf.data(), m_cQuarter.data(), wp / 4, hp / 4, 3);
    // Prediction.
    auto conv = [&](L l, int offset, const HostTensor* up, const HostTensor& same, HostTensor& o) {
        emulateConvRelu(
            hostOperands(layer(l, offset), up, same), ReluOutput { o.data.data(), o.stride });
    };
    auto pool = [&](const HostTensor& in, HostTensor& o) {
        emulatePool(in.data.data(), in.width, in.height, in.stride, o.data.data());
    };
    conv(L::Enc1, 0, nullptr, m_xHalf, m_e1);
    pool(m_e1, m_e1Pool);
    conv(L::Enc2, 0, nullptr, m_e1Pool, m_e2);
    pool(m_e2, m_e2Pool);
    conv(L::Enc3, 0, nullptr, m_e2Pool, m_e3);
    conv(L::Dec2, 0, &m_e3, m_e2, m_d2);
    conv(L::Dec1, 0, &m_d2, m_e1, m_d1);
    // Filtering and fusion.
    auto head = [&](L l, const HostTensor* up, const HostTensor& same, std::vector<float>& logits) {
        const HostLayer& h = layer(l);
        emulateConvLinear(
            hostOperands(h, up, same), LinearOutput { logits.data(), h.packed.outChannels });
    };
    head(L::Head3, nullptr, m_d2, m_h3);
    head(L::Head2, nullptr, m_d1, m_h2);
    head(L::Head1, &m_d1, m_x, m_h1);
    auto filter = [&](L l, const std::vector<float>& logits, const std::vector<float>& color,
                      std::vector<float>& o, int w, int h) {
        emulateLargeFilter(LargeFilterArgs {
            logits.data(), layer(l).packed.outChannels, color.data(), o.data(), w, h });
    };
    filter(L::Head3, m_h3, m_cQuarter, m_f3, wp / 4, hp / 4);
    filter(L::Head2, m_h2, m_cHalf, m_f2, wp / 2, hp / 2);
    filter(L::Head1, m_h1, m_c, m_fused, wp, hp);
    emulateFuseScales(m_f2.data(), m_f3.data(), m_h2.data(), layer(L::Head2).packed.outChannels,
        kLargeTaps, wp / 2, hp / 2);
    emulateFuseScales(m_fused.data(), m_f2.data(), m_h1.data(), layer(L::Head1).packed.outChannels,
        kLargeTaps, wp, hp);
    // Refinement.
    for (int m = 0; m < kLargeRefineModules; ++m) {
        const int first = m * kLargeRefineLayers;
        const float* o = m == 0 ? m_fused.data() : m_refined.data();
        emulateLargeRefineInput(o, m_x.data.data(), m_refineInput.data.data(), wp, hp);
        conv(L::RefA1, first, nullptr, m_refineInput, m_r1);
        conv(L::RefA1, first + 1, nullptr, m_r1, m_r2);
        emulateConvFinal(hostOperands(layer(L::RefA1, first + 2), nullptr, m_r2),
            largeRefinementOutput(m, out, m_refined.data(), wp, hp, o));
    }
}

} // namespace afntest
