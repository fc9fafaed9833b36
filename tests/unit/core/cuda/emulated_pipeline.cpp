// SPDX-License-Identifier: Apache-2.0
// The CUDA afn filter on the CPU (see emulated_pipeline.h): cuda/afn_pipeline.cpp's buffers and
// stage order over the emulated kernels of cuda_emulator.h.
#include "emulated_pipeline.h"

#include "base/exception.h"
#include "methods/afn/work_rows.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace afntest {

using namespace afn::cuda;

EmulatedAfnPipeline::EmulatedAfnPipeline(const afn::afnet::Network& net)
    : m_variant(net.variant())
    , m_refine(net.variant() == afn::afnet::Variant::Full)
    , m_historyInput(net.hasHistoryInput())
    , m_albedoTrust(net.hasAlbedoTrust())
    , m_quarter(net.hasQuarterScale())
{
    if (m_albedoTrust)
        m_trustHead = packTrustHead(net.albedoTrustHead());
    if (m_quarter)
        m_head4.packed = packConv(net.quarterHead(), 0);
    if (m_variant == afn::afnet::Variant::Large) {
        m_large.setNetwork(net.large());
        return;
    }
    using L = afn::afnet::Network::Layer;
    for (int i = 0; i < 10; ++i) {
        const auto which = static_cast<L>(i);
        if (!m_refine && i >= static_cast<int>(L::Ref1))
            continue;
        int up = 0;
        if (which == L::Dec2)
            up = net.layer(L::Enc3).outChannels();
        else if (which == L::Dec1)
            up = net.layer(L::Dec2).outChannels();
        else if (which == L::HeadTa)
            up = net.layer(L::Dec1).outChannels();
        m_layers[i].packed = packConv(net.layer(which), up);
    }
}

void EmulatedAfnPipeline::allocate(const afn::Frame& f)
{
    using L = afn::afnet::Network::Layer;
    if (f.width == m_width && f.height == m_height)
        return;
    m_width = f.width;
    m_height = f.height;
    m_paddedWidth = paddedSize(m_width);
    m_paddedHeight = paddedSize(m_height);
    const std::size_t n = static_cast<std::size_t>(m_width) * m_height;
    const float nan = std::nanf("");
    m_irradiance.assign(3 * n, nan);
    m_output.assign(3 * n, nan);
    for (int s = 0; s < 2; ++s) {
        m_accumulated[s].assign(3 * n, nan);
        m_history[s].assign(n, nan);
    }
    const std::size_t blocksX = (m_width + kTrustBlockDevice - 1) / kTrustBlockDevice;
    const std::size_t blocks = blocksX * ((m_height + kTrustBlockDevice - 1) / kTrustBlockDevice);
    m_trustRowSums.assign(static_cast<std::size_t>(m_height) * blocksX * kTrustSums, nan);
    m_trustRaw.assign(blocks, nan);
    m_trustCount.assign(blocks, nan);
    m_trustBlock.assign(blocks, nan);
    for (auto& v : m_auxFlags)
        v.assign(n, nan);
    for (auto& v : m_auxEdges)
        v.assign(n, nan);
    for (auto& v : m_auxHistory)
        v.assign(kAuxHistoryStride * n, nan);
    std::memset(&m_auxState, 0xff, sizeof(m_auxState)); // as poisoned device memory
    auto ch = [&](L l) { return m_layers[static_cast<int>(l)].packed.outChannels; };
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    if (m_variant == afn::afnet::Variant::Large) { // AfnPipeline::allocate
        m_large.allocate(wp, hp);
        return;
    }
    const int inputs = m_historyInput ? kHistoryInputChannels : kInputChannels;
    m_x.allocate(wp, hp, inputs);
    m_xHalf.allocate(wp / 2, hp / 2, inputs);
    m_e1.allocate(wp / 2, hp / 2, ch(L::Enc1));
    m_e1Pool.allocate(wp / 4, hp / 4, ch(L::Enc1));
    m_e2.allocate(wp / 4, hp / 4, ch(L::Enc2));
    m_e2Pool.allocate(wp / 8, hp / 8, ch(L::Enc2));
    m_e3.allocate(wp / 8, hp / 8, ch(L::Enc3));
    m_d2.allocate(wp / 4, hp / 4, ch(L::Dec2));
    m_d1.allocate(wp / 2, hp / 2, ch(L::Dec1));
    m_color1Half.assign(3 * static_cast<std::size_t>(wp / 2) * (hp / 2), nan);
    if (m_albedoTrust) {
        m_trust.assign(static_cast<std::size_t>(wp / 2) * (hp / 2), nan);
        m_colorTaScaled.assign(3 * static_cast<std::size_t>(wp) * hp, nan);
    }
    if (m_refine || m_quarter) {
        m_fused.assign(3 * static_cast<std::size_t>(wp) * hp, nan);
        m_refineInput.allocate(wp, hp, kRefineInputChannels);
    }
    if (m_refine) {
        m_r1.allocate(wp, hp, ch(L::Ref1));
        m_r2.allocate(wp, hp, ch(L::Ref2));
    }
}

void EmulatedAfnPipeline::run(const afn::Frame& f, const FrameConstants& c, afn::Image& out)
{
    using L = afn::afnet::Network::Layer;
    allocate(f);
    const int s = m_slot, p = s ^ 1;
    // Upload.
    m_color.assign(f.color.data(), f.color.data() + f.color.size());
    m_albedoRaw.assign(f.albedo.data(), f.albedo.data() + f.albedo.size());
    m_motion.assign(f.motion.data(), f.motion.data() + f.motion.size());
    m_position[s].assign(f.position.data(), f.position.data() + f.position.size());
    m_normalRaw.assign(f.normal.data(), f.normal.data() + f.normal.size());
    m_depthRaw.assign(f.depth.data(), f.depth.data() + f.depth.size());
    // The prefilter's outputs (written for every pixel).
    m_albedo.assign(f.albedo.size(), std::nanf(""));
    m_normal[s].assign(f.normal.size(), std::nanf(""));
    m_depth[s].assign(f.depth.size(), std::nanf(""));
    auto ptr = [](std::vector<float>& v) { return v.empty() ? nullptr : v.data(); };

    // TemporalFeatures.
    std::uint32_t range[2] = { kEmptyRangeMin, kEmptyRangeMax };
    TemporalBuffers b;
    b.width = m_width;
    b.height = m_height;
    b.color = m_color.data();
    b.albedo = ptr(m_albedo);
    b.motion = ptr(m_motion);
    b.position = ptr(m_position[s]);
    b.prevPosition = f.hasPosition() ? m_position[p].data() : nullptr;
    b.normal = ptr(m_normal[s]);
    b.prevNormal = f.hasNormal() ? m_normal[p].data() : nullptr;
    b.depth = ptr(m_depth[s]);
    b.prevDepth = f.hasDepth() ? m_depth[p].data() : nullptr;
    b.prevAccumulated = m_accumulated[p].data();
    b.prevHistoryLength = m_history[p].data();
    b.irradiance = m_irradiance.data();
    b.accumulated = m_accumulated[s].data();
    b.historyLength = m_history[s].data();
    AuxBuffers ab;
    ab.width = m_width;
    ab.height = m_height;
    ab.albedo = ptr(m_albedoRaw);
    ab.normal = ptr(m_normalRaw);
    ab.depth = ptr(m_depthRaw);
    for (int k = 0; k < 3; ++k)
        ab.flags[k] = m_auxFlags[k].data();
    for (int k = 0; k < 2; ++k)
        ab.edges[k] = m_auxEdges[k].data();
    ab.albedoOut = ptr(m_albedo);
    ab.normalOut = ptr(m_normal[s]);
    ab.depthOut = ptr(m_depth[s]);
    ab.prevHistory = m_auxHistory[p].data();
    ab.history = m_auxHistory[s].data();
    ab.state = &m_auxState;
    emulateAuxPrefilter(ab, b, c);
    m_albedoImage = afn::Image(m_albedo.empty() ? 0 : m_width, m_albedo.empty() ? 0 : m_height, 3);
    std::copy(m_albedo.begin(), m_albedo.end(), m_albedoImage.data());
    m_normalImage
        = afn::Image(m_normal[s].empty() ? 0 : m_width, m_normal[s].empty() ? 0 : m_height, 3);
    std::copy(m_normal[s].begin(), m_normal[s].end(), m_normalImage.data());
    m_depthImage
        = afn::Image(m_depth[s].empty() ? 0 : m_width, m_depth[s].empty() ? 0 : m_height, 1);
    std::copy(m_depth[s].begin(), m_depth[s].end(), m_depthImage.data());
    TrustBuffers t;
    t.width = m_width;
    t.height = m_height;
    t.blocksX = (m_width + kTrustBlockDevice - 1) / kTrustBlockDevice;
    t.blocksY = (m_height + kTrustBlockDevice - 1) / kTrustBlockDevice;
    t.rowSums = m_trustRowSums.data();
    t.raw = m_trustRaw.data();
    t.count = m_trustCount.data();
    t.block = m_trustBlock.data();
    unsigned cutPixels = 0;
    t.cutPixels = &cutPixels;
    emulateTemporal(b, t, c, range);
    m_cutShare = cutPixels / (static_cast<double>(m_width) * m_height);
    // AfnPipeline::networkSources and the undemodulation of enqueueFirstStage.
    const afn::afnet::InputSet& use = m_networkInputs;
    const std::size_t values = 3 * static_cast<std::size_t>(m_width) * m_height;
    const float* irradiance = m_irradiance.data();
    const float* accumulated = m_accumulated[s].data();
    if (f.hasAlbedo() && !use.albedo) {
        const float* sources[2] = { irradiance, accumulated };
        for (int k = 0; k < 2; ++k) {
            m_radianceInputs[k].assign(values, std::nanf(""));
            if (k == 0 || use.temporal)
                emulateUndemodulate(sources[k], m_albedo.data(), c.colorDemodulated != 0,
                    m_radianceInputs[k].data(), m_width, m_height);
        }
        irradiance = m_radianceInputs[0].data();
        accumulated = m_radianceInputs[1].data();
    }
    NetworkSources src;
    src.color1 = use.temporal && m_variant == afn::afnet::Variant::Ta ? accumulated : irradiance;
    src.colorTa = !use.temporal                    ? src.color1
        : m_variant == afn::afnet::Variant::OneSpp ? irradiance
                                                   : accumulated;
    // The highlight bypass (AfnPipeline::enqueueFirstStage): the limit from the network inputs'
    // TA colour, both colours clamped.
    const float* highlightSource = use.temporal ? accumulated : irradiance;
    const float limit = emulateHighlightLimit(highlightSource, m_width, m_height, c.highlights);
    for (int k = 0; k < 2; ++k)
        m_highlightClamped[k].assign(values, std::nanf(""));
    emulateHighlightClamp(src.color1, limit, m_highlightClamped[0].data(), m_width, m_height);
    emulateHighlightClamp(src.colorTa, limit, m_highlightClamped[1].data(), m_width, m_height);
    src.color1 = m_highlightClamped[0].data();
    src.colorTa = m_highlightClamped[1].data();
    src.albedo = use.albedo ? b.albedo : nullptr;
    src.normal = use.normal ? b.normal : nullptr;
    src.depth = use.depth ? b.depth : nullptr;
    src.historyLength = m_historyInput && use.temporal ? m_history[s].data() : nullptr;
    FinalOutput fo;
    fo.fused = m_fused.data();
    fo.albedo = src.albedo;
    fo.plainAlbedo = c.colorDemodulated;
    fo.trust = m_albedoTrust ? m_trust.data() : nullptr;
    fo.trustWidth = m_paddedWidth / 2;
    // Work skipping (AfnPipeline::upload, skipsRows()).
    std::vector<char> computed(static_cast<std::size_t>(m_height), 1);
    if (f.hasWorkMask() && !(m_fast && m_refine) && !m_high
        && m_variant != afn::afnet::Variant::Large && !m_quarter) {
        afn::Image grown;
        computed = afn::afnet::computedRows(
            f.work, afn::afnet::workMargin(m_taa, m_postFilter), m_height, grown);
    }
    const std::vector<unsigned char> rows(computed.begin(), computed.end());
    fo.computedRows = rows.data();
    fo.cheap = src.colorTa;
    fo.data = m_output.data();
    fo.width = m_width;
    fo.height = m_height;
    if (!m_high) {
        runNetwork(src, fo, range);
    } else { // AfnPipeline::enqueueNetwork
        const std::size_t n = static_cast<std::size_t>(m_width) * m_height;
        const float* given[6]
            = { src.color1, src.colorTa, src.albedo, src.normal, src.depth, src.historyLength };
        std::vector<float> flipped[6], passOut(3 * n, std::nanf("")), passSum(3 * n);
        for (int pass = 0; pass < kHighTierPasses; ++pass) {
            const bool fx = (pass & 1) != 0, fy = (pass & 2) != 0;
            NetworkSources mirrored = src;
            const float** slots[6] = { &mirrored.color1, &mirrored.colorTa, &mirrored.albedo,
                &mirrored.normal, &mirrored.depth, &mirrored.historyLength };
            if (pass > 0)
                for (int k = 0; k < 6; ++k) {
                    if (!given[k])
                        continue;
                    flipped[k].assign(kNetworkSourceChannels[k] * n, std::nanf(""));
                    emulateFlip(given[k], flipped[k].data(), kNetworkSourceChannels[k], m_width,
                        m_height, fx, fy);
                    *slots[k] = flipped[k].data();
                }
            FinalOutput out = fo;
            out.albedo = mirrored.albedo;
            out.computedRows = nullptr;
            out.demodulated = 1;
            out.data = passOut.data();
            runNetwork(mirrored, out, range);
            emulateAddPass(passOut.data(), passSum.data(), m_width, m_height, fx, fy, pass == 0);
        }
        FinalOutput mean = fo;
        mean.trust = nullptr;
        mean.computedRows = nullptr;
        emulateAveragePasses(passSum.data(), mean);
    }

    const float* albedoOut = use.albedo ? b.albedo : nullptr;
    if (!m_postFilter) // AfnPipeline::enqueueTaa
        emulateHighlightExcess(highlightSource, albedoOut, c.colorDemodulated != 0, limit,
            m_output.data(), m_width, m_height);
    m_radianceImage = afn::Image(m_width, m_height, 3);
    std::copy(m_output.begin(), m_output.end(), m_radianceImage.data());
    // Taa.
    const std::size_t n = static_cast<std::size_t>(m_width) * m_height;
    if (m_taa) {
        for (auto& h : m_taaHistory)
            if (h.size() != 3 * n)
                h.assign(3 * n, std::nanf(""));
        TaaBuffers ta;
        ta.width = m_width;
        ta.height = m_height;
        ta.current = m_output.data();
        ta.history = m_taaHistory[p].data();
        ta.out = m_taaHistory[s].data();
        FrameConstants tc = c; // AfnPipeline::upload
        tc.taaHistory = m_taaRan && c.hasHistory ? 1 : 0;
        emulateTaa(ta, b, trustMeasured(c.hasHistory, c.antilag) ? &t : nullptr, tc);
        if (!m_postFilter)
            m_output = m_taaHistory[s];
    }
    m_taaRan = m_taa;
    // PostFilter.
    if (m_postFilter) {
        m_postPlanes.assign(9 * n, std::nanf(""));
        m_postScratch0.assign(3 * n, std::nanf(""));
        m_postScratch1.assign(3 * n, std::nanf(""));
        PostFilterSources ps;
        ps.width = m_width;
        ps.height = m_height;
        ps.albedo = ptr(m_albedo);
        ps.normal = ptr(m_normal[s]);
        ps.depth = ptr(m_depth[s]);
        ps.irradiance = m_irradiance.data();
        ps.historyLength = m_history[s].data();
        ps.maxSamples = effectiveSamplesLimit(c.alphaMin);
        PostFilterPlanes g;
        float** ordered[9] = { &g.a0, &g.a1, &g.a2, &g.n0, &g.n1, &g.n2, &g.nv, &g.z, &g.ls };
        for (int k = 0; k < 9; ++k)
            *ordered[k] = m_postPlanes.data() + k * n;
        const float* in = m_taa ? m_taaHistory[s].data() : m_output.data();
        emulatePostFilter(ps, g, in, m_output.data(), m_postScratch0.data(), m_postScratch1.data());
        emulateHighlightExcess(highlightSource, albedoOut, c.colorDemodulated != 0, limit,
            m_output.data(), m_width, m_height);
    }

    out = afn::Image(m_width, m_height, 3);
    std::copy(m_output.begin(), m_output.end(), out.data());
    m_irradianceImage = afn::Image(m_width, m_height, 3);
    std::copy(m_irradiance.begin(), m_irradiance.end(), m_irradianceImage.data());
    m_accumulatedImage = afn::Image(m_width, m_height, 3);
    std::copy(m_accumulated[s].begin(), m_accumulated[s].end(), m_accumulatedImage.data());
    m_historyLengthImage = afn::Image(m_width, m_height, 1);
    std::copy(m_history[s].begin(), m_history[s].end(), m_historyLengthImage.data());
    m_slot ^= 1;
}

void EmulatedAfnPipeline::runNetwork(
    const NetworkSources& src, const FinalOutput& fo, const std::uint32_t* range)
{
    if (m_variant == afn::afnet::Variant::Large) // AfnPipeline's stages for AFN large
        return m_large.run(LargeSources { m_width, m_height, src.color1, src.albedo, src.normal,
                               src.depth, range },
            fo);
    using L = afn::afnet::Network::Layer;
    PrepareBuffers pb;
    pb.width = m_width;
    pb.height = m_height;
    pb.paddedWidth = m_paddedWidth;
    pb.paddedHeight = m_paddedHeight;
    pb.color1 = src.color1;
    pb.colorTa = src.colorTa;
    pb.albedo = src.albedo;
    pb.normal = src.normal;
    pb.depth = src.depth;
    pb.depthRange = range;
    pb.historyChannel = m_historyInput ? 1 : 0;
    pb.historyLength = src.historyLength;
    pb.x = m_x.data.data();
    pb.xHalf = m_xHalf.data.data();
    pb.color1Half = m_color1Half.data();
    emulatePrepare(pb);

    // KernelPrediction.
    auto layer = [&](L l) -> const Layer& { return m_layers[static_cast<int>(l)]; };
    auto conv = [&](L l, const Tensor* up, const Tensor& same, Tensor& o) {
        emulateConvRelu(operands(layer(l), up, same), ReluOutput { o.data.data(), o.stride });
    };
    auto pool = [&](const Tensor& in, Tensor& o) {
        emulatePool(in.data.data(), in.width, in.height, in.stride, o.data.data());
    };
    conv(L::Enc1, nullptr, m_xHalf, m_e1);
    if (m_albedoTrust) {
        AlbedoTrustBuffers at;
        at.width = m_width;
        at.height = m_height;
        at.halfWidth = m_e1.width;
        at.halfHeight = m_e1.height;
        at.e1 = m_e1.data.data();
        at.e1Stride = m_e1.stride;
        at.e1Channels = layer(L::Enc1).packed.outChannels;
        at.head = m_trustHead.data();
        at.albedo = src.albedo;
        at.color1 = src.color1;
        at.colorTa = src.colorTa;
        at.trust = m_trust.data();
        at.colorTaScaled = m_colorTaScaled.data();
        at.color1Half = m_color1Half.data();
        emulateAlbedoTrust(at);
    }
    pool(m_e1, m_e1Pool);
    conv(L::Enc2, nullptr, m_e1Pool, m_e2);
    pool(m_e2, m_e2Pool);
    conv(L::Enc3, nullptr, m_e2Pool, m_e3);
    conv(L::Dec2, &m_e3, m_e2, m_d2);
    conv(L::Dec1, &m_d2, m_e1, m_d1);

    // FilteringFusion.
    const bool refines = m_refine && !m_fast;
    FilterFuseArgs a;
    a.head1 = operands(layer(L::Head1), nullptr, m_d1);
    a.headTa = operands(layer(L::HeadTa), &m_d1, m_x);
    a.x = m_x.data.data();
    a.colorTa = m_albedoTrust
        ? PaddedColor { m_colorTaScaled.data(), m_paddedWidth, m_paddedHeight, m_paddedWidth,
              m_paddedHeight }
        : PaddedColor { src.colorTa, m_width, m_height, m_paddedWidth, m_paddedHeight };
    a.color1Half = PlainColor { m_color1Half.data(), m_paddedWidth / 2, m_paddedHeight / 2 };
    if (refines || m_quarter) {
        a.fused = m_fused.data();
        a.refineInput = m_refineInput.data.data();
    } else {
        a.output = fo;
    }
    emulateFilterFuse(a);
    if (m_quarter) // AfnPipeline::enqueueQuarterScale
        emulateQuarterScale(refines, fo);

    // Refinement.
    if (refines) {
        conv(L::Ref1, nullptr, m_refineInput, m_r1);
        conv(L::Ref2, nullptr, m_r1, m_r2);
        emulateConvFinal(operands(layer(L::Ref3), nullptr, m_r2), fo);
    }
}

void EmulatedAfnPipeline::emulateQuarterScale(bool refines, const FinalOutput& fo)
{
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    const std::size_t quarter = static_cast<std::size_t>(wp / 4) * (hp / 4);
    const int logits = m_head4.packed.outChannels;
    std::vector<float> half(12 * quarter), low(3 * quarter), head(logits * quarter),
        delta(3 * quarter);
    emulateDown2(m_fused.data(), half.data(), wp / 2, hp / 2, 3);
    emulateDown2(half.data(), low.data(), wp / 4, hp / 4, 3);
    emulateConvLinear(operands(m_head4, nullptr, m_d2), LinearOutput { head.data(), logits });
    emulateQuarterDelta(
        QuarterArgs { head.data(), logits, low.data(), delta.data(), wp / 4, hp / 4 });
    emulateAddUpsampled4(delta.data(), m_fused.data(), wp, hp);
    if (refines)
        emulateRefineInput(m_fused.data(), m_x.data.data(), m_refineInput.data.data(), wp, hp);
    else
        emulateFusedOutput(m_fused.data(), wp, fo);
}

afn::Image EmulatedAfnPipeline::networkInput() const
{
    if (m_variant == afn::afnet::Variant::Large)
        return m_large.input().toImage(kLargeInputChannels);
    return m_x.toImage(m_historyInput ? kHistoryInputChannels : kInputChannels);
}

afn::Image EmulatedAfnPipeline::albedoTrust() const
{
    afn::Image t(m_paddedWidth / 2, m_paddedHeight / 2, 1);
    std::copy(m_trust.begin(), m_trust.end(), t.data());
    return t;
}

afn::Image EmulatedAfnPipeline::decoderOutput() const
{
    return m_d1.toImage(
        m_layers[static_cast<int>(afn::afnet::Network::Layer::Dec1)].packed.outChannels);
}

} // namespace afntest
