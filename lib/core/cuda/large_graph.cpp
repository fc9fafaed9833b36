// SPDX-License-Identifier: Apache-2.0
// AFN large on one GPU (see cuda/large_graph.h).
#include "cuda/large_graph.h"

#include "base/exception.h"

namespace afn::cuda {

void LargeGraph::setNetwork(const afnet::LargeNetwork& net, cudaStream_t stream)
{
    for (int i = 0; i < afnet::LargeNetwork::kLayers; ++i) {
        int up = 0; // channels of the half-size input of concat(U(up), same)
        if (i == static_cast<int>(L::Dec2))
            up = net.layer(static_cast<int>(L::Enc3)).outChannels();
        else if (i == static_cast<int>(L::Dec1))
            up = net.layer(static_cast<int>(L::Dec2)).outChannels();
        else if (i == static_cast<int>(L::Head1))
            up = net.layer(static_cast<int>(L::Dec1)).outChannels();
        m_layers[i].upload(net.layer(i), up, stream);
    }
    AFN_CUDA_CHECK(cudaStreamSynchronize(stream));
    m_paddedWidth = m_paddedHeight = 0; // channel counts may differ: allocate again
}

void LargeGraph::release()
{
    *this = LargeGraph {};
}

void LargeGraph::allocate(int wp, int hp, bool p, cudaStream_t st)
{
    const auto channels = [&](L l, int offset = 0) { return layer(l, offset).packed.outChannels; };
    m_x.allocate(wp, hp, kLargeInputChannels, p, st);
    m_xHalf.allocate(wp / 2, hp / 2, kLargeInputChannels, p, st);
    m_e1.allocate(wp / 2, hp / 2, channels(L::Enc1), p, st);
    m_e1Pool.allocate(wp / 4, hp / 4, channels(L::Enc1), p, st);
    m_e2.allocate(wp / 4, hp / 4, channels(L::Enc2), p, st);
    m_e2Pool.allocate(wp / 8, hp / 8, channels(L::Enc2), p, st);
    m_e3.allocate(wp / 8, hp / 8, channels(L::Enc3), p, st);
    m_d2.allocate(wp / 4, hp / 4, channels(L::Dec2), p, st);
    m_d1.allocate(wp / 2, hp / 2, channels(L::Dec1), p, st);
    const std::size_t full = pixelCount(wp, hp), half = pixelCount(wp / 2, hp / 2);
    const std::size_t quarter = pixelCount(wp / 4, hp / 4);
    allocateBuffer(m_c, 3 * full, p, st);
    allocateBuffer(m_cHalf, 3 * half, p, st);
    allocateBuffer(m_cQuarter, 3 * quarter, p, st);
    allocateBuffer(m_h1, channels(L::Head1) * full, p, st);
    allocateBuffer(m_h2, channels(L::Head2) * half, p, st);
    allocateBuffer(m_h3, channels(L::Head3) * quarter, p, st);
    allocateBuffer(m_f2, 3 * half, p, st);
    allocateBuffer(m_f3, 3 * quarter, p, st);
    allocateBuffer(m_fused, 3 * full, p, st);
    allocateBuffer(m_refined, 3 * full, p, st);
    m_refineInput.allocate(wp, hp, kLargeInputChannels, p, st);
    m_r1.allocate(wp, hp, channels(L::RefA1), p, st);
    m_r2.allocate(wp, hp, channels(L::RefA1, 1), p, st);
    m_paddedWidth = wp;
    m_paddedHeight = hp;
}

void LargeGraph::enqueuePrepare(const LargeSources& src, cudaStream_t stream) const
{
    if (m_paddedWidth != paddedSize(src.width) || m_paddedHeight != paddedSize(src.height))
        throwInvalidOperation("CUDA afn: AFN large is not allocated for this frame");
    launchLargePrepare(largePrepareBuffers(src, m_paddedWidth, m_paddedHeight, m_x.data.data(),
                           m_xHalf.data.data(), m_c.data(), m_cHalf.data()),
        stream);
    launchDown2(
        m_cHalf.data(), m_cQuarter.data(), m_paddedWidth / 4, m_paddedHeight / 4, 3, stream);
}

void LargeGraph::enqueuePrediction(cudaStream_t stream) const
{
    auto conv = [&](L l, const HalfTensor* up, const HalfTensor& same, const HalfTensor& out) {
        launchConvRelu(
            convOperands(layer(l), up, same), ReluOutput { out.data.data(), out.stride }, stream);
    };
    auto pool = [&](const HalfTensor& in, const HalfTensor& out) {
        launchPool(in.data.data(), in.width, in.height, in.stride, out.data.data(), stream);
    };
    conv(L::Enc1, nullptr, m_xHalf, m_e1);
    pool(m_e1, m_e1Pool);
    conv(L::Enc2, nullptr, m_e1Pool, m_e2);
    pool(m_e2, m_e2Pool);
    conv(L::Enc3, nullptr, m_e2Pool, m_e3);
    conv(L::Dec2, &m_e3, m_e2, m_d2);
    conv(L::Dec1, &m_d2, m_e1, m_d1);
}

void LargeGraph::enqueueFilteringFusion(cudaStream_t stream) const
{
    auto head = [&](L l, const HalfTensor* up, const HalfTensor& same, float* logits) {
        const DeviceLayer& h = layer(l);
        launchConvLinear(
            convOperands(h, up, same), LinearOutput { logits, h.packed.outChannels }, stream);
    };
    head(L::Head3, nullptr, m_d2, m_h3.data());
    head(L::Head2, nullptr, m_d1, m_h2.data());
    head(L::Head1, &m_d1, m_x, m_h1.data());
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    auto filter = [&](L l, const float* logits, const float* color, float* out, int w, int h) {
        launchLargeFilter(
            LargeFilterArgs { logits, layer(l).packed.outChannels, color, out, w, h }, stream);
    };
    filter(L::Head3, m_h3.data(), m_cQuarter.data(), m_f3.data(), wp / 4, hp / 4);
    filter(L::Head2, m_h2.data(), m_cHalf.data(), m_f2.data(), wp / 2, hp / 2);
    filter(L::Head1, m_h1.data(), m_c.data(), m_fused.data(), wp, hp); // f1, then i in place
    launchFuseScales(m_f2.data(), m_f3.data(), m_h2.data(), layer(L::Head2).packed.outChannels,
        kLargeTaps, wp / 2, hp / 2, stream); // o2
    launchFuseScales(m_fused.data(), m_f2.data(), m_h1.data(), layer(L::Head1).packed.outChannels,
        kLargeTaps, wp, hp, stream); // i
}

void LargeGraph::enqueueRefinement(const FinalOutput& out, cudaStream_t stream) const
{
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    for (int m = 0; m < kLargeRefineModules; ++m) {
        const int first = m * kLargeRefineLayers;
        const float* o = m == 0 ? m_fused.data() : m_refined.data();
        launchLargeRefineInput(o, m_x.data.data(), m_refineInput.data.data(), wp, hp, stream);
        launchConvRelu(convOperands(layer(L::RefA1, first), nullptr, m_refineInput),
            ReluOutput { m_r1.data.data(), m_r1.stride }, stream);
        launchConvRelu(convOperands(layer(L::RefA1, first + 1), nullptr, m_r1),
            ReluOutput { m_r2.data.data(), m_r2.stride }, stream);
        launchConvFinal(convOperands(layer(L::RefA1, first + 2), nullptr, m_r2),
            largeRefinementOutput(m, out, m_refined.data(), wp, hp, o), stream);
    }
}

} // namespace afn::cuda
