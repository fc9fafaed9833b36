// SPDX-License-Identifier: Apache-2.0
// The CUDA afn pipeline's stages (see afn_pipeline.h): the buffers each stage's kernels read and
// write, enqueued in stream order (also inside a graph capture).
#include "cuda/afn_pipeline.h"

#include "base/exception.h"
#include "cuda/check.h"

namespace afn::cuda {

AfnPipeline::NetworkSources AfnPipeline::networkSources(int slot) const
{
    NetworkSources src = givenSources(slot);
    src.color1 = m_highlightClamped[0].data();
    src.colorTa = m_highlightClamped[1].data();
    return src;
}

const float* AfnPipeline::highlightSource(int slot) const
{
    // NetworkInputs::colorTa() whatever the variant: the TA colour of a temporal model, else the
    // frame's, times the albedo for a model without it.
    const bool radiance = undemodulates(m_layout);
    if (m_networkInputs.temporal)
        return radiance ? m_radianceInputs[1].data() : m_accumulated[slot].data();
    return radiance ? m_radianceInputs[0].data() : m_irradiance.data();
}

AfnPipeline::NetworkSources AfnPipeline::givenSources(int slot) const
{
    const FrameLayout& l = m_layout;
    const afnet::InputSet& use = m_networkInputs;
    // The colours (network_inputs.cpp prepare()): times the albedo for a model without it.
    const bool radiance = undemodulates(l);
    const float* irradiance = radiance ? m_radianceInputs[0].data() : m_irradiance.data();
    const float* accumulated = radiance ? m_radianceInputs[1].data() : m_accumulated[slot].data();
    // The variants "ta" and "1spp" filter one colour for both branches; without the temporal
    // branch both colours are this frame's.
    NetworkSources src;
    src.color1 = use.temporal && m_variant == afnet::Variant::Ta ? accumulated : irradiance;
    src.colorTa = !use.temporal               ? src.color1
        : m_variant == afnet::Variant::OneSpp ? irradiance
                                              : accumulated;
    src.albedo = l.albedo && use.albedo ? m_albedo.data() : nullptr;
    src.normal = l.normal && use.normal ? m_normal[slot].data() : nullptr;
    src.depth = l.depth && use.depth ? m_depth[slot].data() : nullptr;
    src.historyLength = m_historyInput && use.temporal ? m_history[slot].data() : nullptr;
    return src;
}

TemporalBuffers AfnPipeline::temporalBuffers(int slot) const
{
    const FrameLayout& l = m_layout;
    const int prev = slot ^ 1;
    TemporalBuffers b;
    b.width = l.width;
    b.height = l.height;
    b.color = m_color.data();
    b.albedo = l.albedo ? m_albedo.data() : nullptr;
    b.motion = l.motion ? m_motion.data() : nullptr;
    b.position = l.position ? m_position[slot].data() : nullptr;
    b.prevPosition = l.position ? m_position[prev].data() : nullptr;
    b.normal = l.normal ? m_normal[slot].data() : nullptr;
    b.prevNormal = l.normal ? m_normal[prev].data() : nullptr;
    b.depth = l.depth ? m_depth[slot].data() : nullptr;
    b.prevDepth = l.depth ? m_depth[prev].data() : nullptr;
    b.prevAccumulated = m_accumulated[prev].data();
    b.prevHistoryLength = m_history[prev].data();
    b.irradiance = m_irradiance.data();
    b.accumulated = m_accumulated[slot].data();
    b.historyLength = m_history[slot].data();
    return b;
}

TrustBuffers AfnPipeline::trustBuffers() const
{
    const FrameLayout& l = m_layout;
    TrustBuffers t;
    t.width = l.width;
    t.height = l.height;
    t.blocksX = (l.width + kTrustBlockDevice - 1) / kTrustBlockDevice;
    t.blocksY = (l.height + kTrustBlockDevice - 1) / kTrustBlockDevice;
    t.rowSums = m_trustRowSums.data();
    t.raw = m_trustRaw.data();
    t.count = m_trustCount.data();
    t.block = m_trustBlock.data();
    t.cutPixels = m_cutPixels.data();
    return t;
}

void AfnPipeline::enqueueFirstStage(int slot, cudaStream_t stream) const
{
    const FrameLayout& l = m_layout;
    const int prev = slot ^ 1;
    const TemporalBuffers b = temporalBuffers(slot);
    AuxBuffers a;
    a.width = l.width;
    a.height = l.height;
    a.albedo = l.albedo ? m_albedoRaw.data() : nullptr;
    a.normal = l.normal ? m_normalRaw.data() : nullptr;
    a.depth = l.depth ? m_depthRaw.data() : nullptr;
    for (int k = 0; k < 3; ++k)
        a.flags[k] = m_auxFlags[k].data();
    for (int k = 0; k < 2; ++k)
        a.edges[k] = m_auxEdges[k].data();
    a.albedoOut = l.albedo ? m_albedo.data() : nullptr;
    a.normalOut = l.normal ? m_normal[slot].data() : nullptr;
    a.depthOut = l.depth ? m_depth[slot].data() : nullptr;
    a.prevHistory = m_auxHistory[prev].data();
    a.history = m_auxHistory[slot].data();
    a.state = m_auxState.data();
    launchAuxPrefilter(a, b, m_constants.data(), stream);
    launchResetFrameCounters(m_depthRange.data(), m_cutPixels.data(), stream);
    launchTemporal(b, trustBuffers(), m_constants.data(), m_depthRange.data(), stream);
    if (undemodulates(l)) { // a model without albedo on a frame with one
        const bool plain = l.colorDemodulated;
        launchUndemodulate(m_irradiance.data(), m_albedo.data(), plain, m_radianceInputs[0].data(),
            l.width, l.height, stream);
        if (m_networkInputs.temporal)
            launchUndemodulate(m_accumulated[slot].data(), m_albedo.data(), plain,
                m_radianceInputs[1].data(), l.width, l.height, stream);
    }
    // The highlight bypass (stages/highlight_bypass.h): the limit from the network's own TA
    // colour, both colours clamped for the network.
    const NetworkSources given = givenSources(slot);
    launchHighlightLimit(highlightSource(slot), l.width, l.height, m_constants.data(),
        m_highlightCounts.data(), m_highlightLimit.data(), stream);
    launchHighlightClamp(given.color1, m_highlightLimit.data(), m_highlightClamped[0].data(),
        l.width, l.height, stream);
    launchHighlightClamp(given.colorTa, m_highlightLimit.data(), m_highlightClamped[1].data(),
        l.width, l.height, stream);
}

void AfnPipeline::enqueueHighlightExcess(int slot, cudaStream_t stream) const
{
    const FrameLayout& l = m_layout;
    launchHighlightExcess(highlightSource(slot), networkSources(slot).albedo, l.colorDemodulated,
        m_highlightLimit.data(), m_output.data(), l.width, l.height, stream);
}

void AfnPipeline::enqueueTemporalFeatures(int slot, cudaStream_t stream) const
{
    enqueueFirstStage(slot, stream);
    enqueuePrepare(networkSources(slot), stream);
}

void AfnPipeline::enqueuePrepare(const NetworkSources& src, cudaStream_t stream) const
{
    if (large()) {
        const LargeSources ls { m_layout.width, m_layout.height, src.color1, src.albedo, src.normal,
            src.depth, m_depthRange.data() };
        return m_large.enqueuePrepare(ls, stream);
    }
    PrepareBuffers p;
    p.width = m_layout.width;
    p.height = m_layout.height;
    p.paddedWidth = m_paddedWidth;
    p.paddedHeight = m_paddedHeight;
    p.color1 = src.color1;
    p.colorTa = src.colorTa;
    p.albedo = src.albedo;
    p.normal = src.normal;
    p.depth = src.depth;
    p.depthRange = m_depthRange.data();
    p.historyChannel = m_historyInput ? 1 : 0;
    p.historyLength = src.historyLength;
    p.x = m_x.data.data();
    p.xHalf = m_xHalf.data.data();
    p.color1Half = m_color1Half.data();
    launchPrepare(p, stream);
}

void AfnPipeline::enqueueKernelPrediction(const NetworkSources& src, cudaStream_t stream) const
{
    if (large())
        return m_large.enqueuePrediction(stream);
    auto conv = [&](NetLayer l, const Tensor* up, const Tensor& same, const Tensor& out) {
        launchConvRelu(
            operands(layer(l), up, same), ReluOutput { out.data.data(), out.stride }, stream);
    };
    auto pool = [&](const Tensor& in, const Tensor& out) {
        launchPool(in.data.data(), in.width, in.height, in.stride, out.data.data(), stream);
    };
    conv(NetLayer::Enc1, nullptr, m_xHalf, m_e1);
    if (m_albedoTrust) {
        AlbedoTrustBuffers t;
        t.width = m_layout.width;
        t.height = m_layout.height;
        t.halfWidth = m_e1.width;
        t.halfHeight = m_e1.height;
        t.e1 = m_e1.data.data();
        t.e1Stride = m_e1.stride;
        t.e1Channels = layer(NetLayer::Enc1).packed.outChannels;
        t.head = m_trustHead.data();
        t.albedo = src.albedo;
        t.color1 = src.color1;
        t.colorTa = src.colorTa;
        t.trust = m_trust.data();
        t.colorTaScaled = m_colorTaScaled.data();
        t.color1Half = m_color1Half.data();
        launchAlbedoTrust(t, stream);
    }
    pool(m_e1, m_e1Pool);
    conv(NetLayer::Enc2, nullptr, m_e1Pool, m_e2);
    pool(m_e2, m_e2Pool);
    conv(NetLayer::Enc3, nullptr, m_e2Pool, m_e3);
    conv(NetLayer::Dec2, &m_e3, m_e2, m_d2);
    conv(NetLayer::Dec1, &m_d2, m_e1, m_d1);
}

FinalOutput AfnPipeline::finalOutput(int slot) const
{
    FinalOutput o;
    o.fused = m_fused.data();
    o.albedo = networkSources(slot).albedo; // null for a model without albedo: not remodulated
    o.plainAlbedo = m_layout.colorDemodulated ? 1 : 0;
    o.trust = m_albedoTrust ? m_trust.data() : nullptr;
    o.trustWidth = m_paddedWidth / 2;
    o.computedRows = m_computedRows.data();
    o.cheap = networkSources(slot).colorTa; // the network's own TA input (Network::run)
    o.data = m_output.data();
    o.width = m_layout.width;
    o.height = m_layout.height;
    return o;
}

void AfnPipeline::enqueueFilteringFusion(
    const NetworkSources& src, const FinalOutput& out, cudaStream_t stream) const
{
    if (large())
        return m_large.enqueueFilteringFusion(stream);
    FilterFuseArgs a;
    a.head1 = operands(layer(NetLayer::Head1), nullptr, m_d1);
    a.headTa = operands(layer(NetLayer::HeadTa), &m_d1, m_x);
    a.x = m_x.data.data();
    // With the albedo trust the TA colour times s, stored at the padded size.
    a.colorTa.data = m_albedoTrust ? m_colorTaScaled.data() : src.colorTa;
    a.colorTa.width = m_albedoTrust ? m_paddedWidth : m_layout.width;
    a.colorTa.height = m_albedoTrust ? m_paddedHeight : m_layout.height;
    a.colorTa.paddedWidth = m_paddedWidth;
    a.colorTa.paddedHeight = m_paddedHeight;
    a.color1Half.data = m_color1Half.data();
    a.color1Half.width = m_paddedWidth / 2;
    a.color1Half.height = m_paddedHeight / 2;
    if (storesFused()) {
        a.fused = m_fused.data();
        a.refineInput = m_refineInput.data.data();
    } else {
        a.output = out;
    }
    launchFilterFuse(a, stream);
    if (m_quarter)
        enqueueQuarterScale(out, stream);
}

void AfnPipeline::enqueueQuarterScale(const FinalOutput& out, cudaStream_t stream) const
{
    // i += U4(sigmoid(beta) (K * l - l)), l = D(D(i)) (quarter_scale.h), then what the fused
    // kernel would have done with i: the refinement input, or the output.
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    launchDown2(m_fused.data(), m_quarterHalf.data(), wp / 2, hp / 2, 3, stream);
    launchDown2(m_quarterHalf.data(), m_quarterLow.data(), wp / 4, hp / 4, 3, stream);
    const int logits = m_head4.packed.outChannels;
    launchConvLinear(
        operands(m_head4, nullptr, m_d2), LinearOutput { m_quarterLogits.data(), logits }, stream);
    launchQuarterDelta(QuarterArgs { m_quarterLogits.data(), logits, m_quarterLow.data(),
                           m_quarterDelta.data(), wp / 4, hp / 4 },
        stream);
    launchAddUpsampled4(m_quarterDelta.data(), m_fused.data(), wp, hp, stream);
    if (refines())
        launchRefineInput(
            m_fused.data(), m_x.data.data(), m_refineInput.data.data(), wp, hp, stream);
    else
        launchFusedOutput(m_fused.data(), wp, out, stream);
}

void AfnPipeline::enqueueRefinement(const FinalOutput& out, cudaStream_t stream) const
{
    if (large())
        return m_large.enqueueRefinement(out, stream);
    if (!refines())
        return;
    auto conv = [&](NetLayer l, const Tensor& same, const Tensor& out) {
        launchConvRelu(
            operands(layer(l), nullptr, same), ReluOutput { out.data.data(), out.stride }, stream);
    };
    conv(NetLayer::Ref1, m_refineInput, m_r1);
    conv(NetLayer::Ref2, m_r1, m_r2);
    launchConvFinal(operands(layer(NetLayer::Ref3), nullptr, m_r2), out, stream);
}

void AfnPipeline::enqueueNetwork(int slot, cudaStream_t stream) const
{
    const NetworkSources src = networkSources(slot);
    if (!m_high) {
        const FinalOutput out = finalOutput(slot);
        enqueuePrepare(src, stream);
        enqueueKernelPrediction(src, stream);
        enqueueFilteringFusion(src, out, stream);
        enqueueRefinement(out, stream);
        return;
    }
    // quality=high (high_tier_pixel.h): per pass the inputs mirrored, the network's demodulated
    // output (nothing skipped), mirrored back into the sum; then the mean, remodulated.
    const FrameLayout& l = m_layout;
    const float* given[6]
        = { src.color1, src.colorTa, src.albedo, src.normal, src.depth, src.historyLength };
    for (int pass = 0; pass < kHighTierPasses; ++pass) {
        const bool fx = (pass & 1) != 0, fy = (pass & 2) != 0;
        NetworkSources mirrored = src;
        const float** slots[6] = { &mirrored.color1, &mirrored.colorTa, &mirrored.albedo,
            &mirrored.normal, &mirrored.depth, &mirrored.historyLength };
        if (pass > 0)
            for (int k = 0; k < 6; ++k) {
                if (!given[k])
                    continue;
                launchFlip(given[k], m_flipped[k].data(), kNetworkSourceChannels[k], l.width,
                    l.height, fx, fy, stream);
                *slots[k] = m_flipped[k].data();
            }
        FinalOutput out = finalOutput(slot);
        out.albedo = mirrored.albedo; // the albedo of this pass's x (the trust's division)
        out.computedRows = nullptr;
        out.demodulated = 1;
        out.data = m_passOut.data();
        enqueuePrepare(mirrored, stream);
        enqueueKernelPrediction(mirrored, stream);
        enqueueFilteringFusion(mirrored, out, stream);
        enqueueRefinement(out, stream);
        launchAddPass(
            m_passOut.data(), m_passSum.data(), l.width, l.height, fx, fy, pass == 0, stream);
    }
    FinalOutput mean = finalOutput(slot);
    mean.trust = nullptr;
    mean.computedRows = nullptr;
    launchAveragePasses(m_passSum.data(), mean, stream);
}

void AfnPipeline::enqueueTaa(int slot, cudaStream_t stream) const
{
    if (!m_postFilter)
        enqueueHighlightExcess(slot, stream); // before the TAA, whose output is its next history
    if (!m_taa)
        return;
    TaaBuffers a;
    a.width = m_layout.width;
    a.height = m_layout.height;
    a.current = m_output.data();
    a.history = m_taaHistory[slot ^ 1].data();
    a.out = m_taaHistory[slot].data();
    launchTaa(a, temporalBuffers(slot), trustBuffers(), m_constants.data(), stream);
    if (!m_postFilter) // else the post-filter reads the TAA's output and writes the output
        AFN_CUDA_CHECK(cudaMemcpyAsync(
            m_output.data(), a.out, m_output.bytes(), cudaMemcpyDeviceToDevice, stream));
}

void AfnPipeline::enqueuePostFilter(int slot, cudaStream_t stream) const
{
    if (!m_postFilter)
        return;
    const FrameLayout& l = m_layout;
    const std::size_t n = pixelCount(l.width, l.height);
    PostFilterSources s;
    s.width = l.width;
    s.height = l.height;
    s.albedo = l.albedo ? m_albedo.data() : nullptr;
    s.normal = l.normal ? m_normal[slot].data() : nullptr;
    s.depth = l.depth ? m_depth[slot].data() : nullptr;
    s.irradiance = m_irradiance.data();
    s.historyLength = m_history[slot].data();
    float* planes = m_postPlanes.data();
    PostFilterPlanes g;
    float** ordered[9] = { &g.a0, &g.a1, &g.a2, &g.n0, &g.n1, &g.n2, &g.nv, &g.z, &g.ls };
    for (int k = 0; k < 9; ++k)
        *ordered[k] = planes + k * n;
    // After the TAA it filters the TAA's output (kept as its next history), as on the CPU.
    const float* in = m_taa ? m_taaHistory[slot].data() : m_output.data();
    launchPostFilter(s, g, m_constants.data(), in, m_output.data(), m_postScratch0.data(),
        m_postScratch1.data(), stream);
    enqueueHighlightExcess(slot, stream);
}

} // namespace afn::cuda
