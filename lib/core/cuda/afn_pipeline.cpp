// SPDX-License-Identifier: Apache-2.0
// The CUDA afn pipeline (see afn_pipeline.h).
#include "cuda/afn_pipeline.h"

#include "base/exception.h"
#include "cuda/gpu.h"
#include "methods/afn/post_filter.h"
#include "methods/afn/work_rows.h"
#include "stages/temporal_accumulation.h"

namespace afn::cuda {

namespace {

template <typename T>
void uploadImage(DeviceBuffer<T>& dst, const Image& src, std::size_t expected, cudaStream_t stream)
{
    if (src.size() != expected || dst.size() != expected)
        throwInvalidOperation("CUDA afn: an input does not match the configured frame");
    AFN_CUDA_CHECK(
        cudaMemcpyAsync(dst.data(), src.data(), dst.bytes(), cudaMemcpyHostToDevice, stream));
}

/// The aux prefilter's report from its device state (AuxPrefilter::report()).
AuxReport auxReport(const AuxState& s, const FrameLayout& l, double pixels)
{
    AuxReport r;
    r.noisy = s.noisy != 0;
    r.grainLimited = s.grainLimited != 0;
    r.albedoSpeckle = l.albedo ? s.counts[0] / pixels : -1.0;
    r.normalSpeckle = l.normal ? s.counts[1] / pixels : -1.0;
    r.depthSpeckle = l.depth ? s.counts[2] / pixels : -1.0;
    return r;
}

// The device's copies of the aux prefilter's constants.
static_assert(kAuxAlbedoThresholdDevice == AuxNoiseThresholds::albedo);
static_assert(kAuxNormalThresholdDevice == AuxNoiseThresholds::normal);
static_assert(kAuxDepthThresholdDevice == AuxNoiseThresholds::depth);
static_assert(kAuxAlbedoLevelFloorDevice == kAuxAlbedoLevelFloor);
static_assert(kAuxDepthSkyDevice == kAuxDepthSky);
static_assert(kAuxNoisyShareDevice == kAuxNoisyShare);
static_assert(kAuxTrustedSppDevice == kAuxTrustedSpp);
static_assert(kAuxUnreliableShareDevice == kAuxUnreliableShare);
static_assert(kAuxDenseLowDevice == kAuxDenseLow && kAuxDenseHighDevice == kAuxDenseHigh);
static_assert(kAuxAlbedoAlphaMinDevice == kAuxAlbedoAlphaMin);
static_assert(kAuxNoisyAlbedoFloorDevice == kAuxNoisyAlbedoFloor);
static_assert(kAuxGrainLimitDevice == kAuxGrainLimit);
static_assert(kMaxHistoryLengthDevice == kMaxHistoryLength);
static_assert(kPostFilterIterationsDevice == afnet::kPostFilterIterations);
static_assert(kPostFilterSigmaLuminanceDevice == afnet::kPostFilterSigmaLuminance);
static_assert(kPostFilterNoiseReferenceDevice == afnet::kPostFilterNoiseReference);
static_assert(kPostFilterNoiseClampDevice == afnet::kPostFilterNoiseClamp);

} // namespace

bool FrameLayout::operator==(const FrameLayout& o) const
{
    return width == o.width && height == o.height && albedo == o.albedo && normal == o.normal
        && depth == o.depth && position == o.position && motion == o.motion
        && colorDemodulated == o.colorDemodulated;
}

FrameLayout FrameLayout::of(const Frame& f)
{
    FrameLayout l;
    l.width = f.width;
    l.height = f.height;
    l.albedo = f.hasAlbedo();
    l.normal = f.hasNormal();
    l.depth = f.hasDepth();
    l.position = f.hasPosition();
    l.motion = f.hasMotion();
    l.colorDemodulated = f.colorDemodulated;
    return l;
}

AfnPipeline::AfnPipeline(int gpu)
    : m_gpu((useGpu(gpu), gpu)) // the stream below belongs to this GPU
{
}

AfnPipeline::~AfnPipeline()
{
    cudaSetDevice(m_gpu); // the members free their memory on this GPU
}

void AfnPipeline::setNetwork(const afnet::Network& network)
{
    if (!network.loaded())
        throwInvalidOperation("CUDA afn: no network loaded");
    useGpu(m_gpu);
    m_variant = network.variant();
    m_refine = m_variant == afnet::Variant::Full;
    m_historyInput = network.hasHistoryInput();
    m_albedoTrust = network.hasAlbedoTrust();
    m_quarter = network.hasQuarterScale();
    if (m_quarter)
        m_head4.upload(network.quarterHead(), 0, m_stream.get());
    else
        m_head4 = Layer {};
    if (large())
        m_large.setNetwork(network.large(), m_stream.get());
    else
        m_large.release();
    for (int i = 0; i < static_cast<int>(m_layers.size()); ++i) {
        const auto which = static_cast<NetLayer>(i);
        Layer& dst = m_layers[i];
        if (large() || (!m_refine && i >= static_cast<int>(NetLayer::Ref1))) {
            dst = Layer {};
            continue;
        }
        int up = 0; // channels of the half-size input of concat(U(up), same)
        if (which == NetLayer::Dec2)
            up = network.layer(NetLayer::Enc3).outChannels();
        else if (which == NetLayer::Dec1)
            up = network.layer(NetLayer::Dec2).outChannels();
        else if (which == NetLayer::HeadTa)
            up = network.layer(NetLayer::Dec1).outChannels();
        dst.upload(network.layer(which), up, m_stream.get());
    }
    std::vector<float> head; // the albedo trust's head, alive until the copy is done
    if (m_albedoTrust) {
        head = packTrustHead(network.albedoTrustHead());
        m_trustHead.resize(head.size());
        AFN_CUDA_CHECK(cudaMemcpyAsync(m_trustHead.data(), head.data(), m_trustHead.bytes(),
            cudaMemcpyHostToDevice, m_stream.get()));
    } else {
        m_trustHead.release();
    }
    AFN_CUDA_CHECK(cudaStreamSynchronize(m_stream.get()));
    m_hasNetwork = true;
    m_layout = FrameLayout {}; // channel counts may differ: allocate and capture again
    m_graphsValid = false;
}

void AfnPipeline::allocate(const FrameLayout& layout)
{
    const int w = layout.width, h = layout.height;
    const std::size_t n = pixelCount(w, h);
    const bool p = m_poison;
    const cudaStream_t st = m_stream.get();
    allocateBuffer(m_color, 3 * n, p, st);
    allocateBuffer(m_albedo, layout.albedo ? 3 * n : 0, p, st);
    allocateBuffer(m_motion, layout.motion ? 2 * n : 0, p, st);
    allocateBuffer(m_irradiance, 3 * n, p, st);
    for (int k = 0; k < 2; ++k)
        allocateBuffer(m_radianceInputs[k], undemodulates(layout) ? 3 * n : 0, p, st);
    allocateBuffer(m_output, 3 * n, p, st);
    for (auto& c : m_highlightClamped)
        allocateBuffer(c, 3 * n, p, st);
    allocateBuffer(m_highlightCounts, kHighlightBins, p, st);
    allocateBuffer(m_highlightLimit, 1, p, st);
    for (int s = 0; s < 2; ++s) {
        allocateBuffer(m_position[s], layout.position ? 3 * n : 0, p, st);
        allocateBuffer(m_normal[s], layout.normal ? 3 * n : 0, p, st);
        allocateBuffer(m_depth[s], layout.depth ? n : 0, p, st);
        allocateBuffer(m_accumulated[s], 3 * n, p, st);
        allocateBuffer(m_history[s], n, p, st);
    }
    allocateBuffer(m_depthRange, 2, p, st);
    const std::size_t blocksX = (w + kTrustBlockDevice - 1) / kTrustBlockDevice;
    const std::size_t blocks = blocksX * ((h + kTrustBlockDevice - 1) / kTrustBlockDevice);
    allocateBuffer(m_trustRowSums, static_cast<std::size_t>(h) * blocksX * kTrustSums, p, st);
    allocateBuffer(m_trustRaw, blocks, p, st);
    allocateBuffer(m_trustCount, blocks, p, st);
    allocateBuffer(m_trustBlock, blocks, p, st);
    allocateBuffer(m_cutPixels, 1, p, st);
    allocateBuffer(m_computedRows, static_cast<std::size_t>(h), p, st);
    allocateBuffer(m_albedoRaw, layout.albedo ? 3 * n : 0, p, st);
    allocateBuffer(m_normalRaw, layout.normal ? 3 * n : 0, p, st);
    allocateBuffer(m_depthRaw, layout.depth ? n : 0, p, st);
    const bool present[3] = { layout.albedo, layout.normal, layout.depth };
    for (int k = 0; k < 3; ++k)
        allocateBuffer(m_auxFlags[k], present[k] ? n : 0, p, st);
    for (int k = 0; k < 2; ++k) {
        allocateBuffer(m_auxEdges[k], present[k] ? n : 0, p, st);
        allocateBuffer(m_auxHistory[k], layout.albedo ? kAuxHistoryStride * n : 0, p, st);
    }
    allocateBuffer(m_auxState, 1, p, st);
    allocateBuffer(m_postPlanes, m_postFilter ? 9 * n : 0, p, st);
    allocateBuffer(m_postScratch0, m_postFilter ? 3 * n : 0, p, st);
    allocateBuffer(m_postScratch1, m_postFilter ? 3 * n : 0, p, st);
    for (auto& h : m_taaHistory)
        allocateBuffer(h, m_taa ? 3 * n : 0, p, st);
    for (int k = 0; k < 6; ++k)
        allocateBuffer(m_flipped[k], m_high ? kNetworkSourceChannels[k] * n : 0, p, st);
    allocateBuffer(m_passOut, m_high ? 3 * n : 0, p, st);
    allocateBuffer(m_passSum, m_high ? 3 * n : 0, p, st);
    allocateBuffer(m_constants, 1, p, st);

    const auto channels = [&](NetLayer l) { return layer(l).packed.outChannels; };
    m_paddedWidth = paddedSize(w);
    m_paddedHeight = paddedSize(h);
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    if (large()) { // AFN large's own tensors instead of the AFN graph's
        for (Tensor* t : { &m_x, &m_xHalf, &m_e1, &m_e1Pool, &m_e2, &m_e2Pool, &m_e3, &m_d2, &m_d1,
                 &m_refineInput, &m_r1, &m_r2 })
            *t = Tensor {};
        for (DeviceBuffer<float>* b : { &m_color1Half, &m_fused, &m_trust, &m_colorTaScaled })
            b->release();
        m_large.allocate(wp, hp, p, st);
        m_layout = layout;
        return;
    }
    const int inputs = m_historyInput ? kHistoryInputChannels : kInputChannels;
    m_x.allocate(wp, hp, inputs, p, st);
    m_xHalf.allocate(wp / 2, hp / 2, inputs, p, st);
    m_e1.allocate(wp / 2, hp / 2, channels(NetLayer::Enc1), p, st);
    m_e1Pool.allocate(wp / 4, hp / 4, channels(NetLayer::Enc1), p, st);
    m_e2.allocate(wp / 4, hp / 4, channels(NetLayer::Enc2), p, st);
    m_e2Pool.allocate(wp / 8, hp / 8, channels(NetLayer::Enc2), p, st);
    m_e3.allocate(wp / 8, hp / 8, channels(NetLayer::Enc3), p, st);
    m_d2.allocate(wp / 4, hp / 4, channels(NetLayer::Dec2), p, st);
    m_d1.allocate(wp / 2, hp / 2, channels(NetLayer::Dec1), p, st);
    allocateBuffer(m_color1Half, 3 * pixelCount(wp / 2, hp / 2), p, st);
    allocateBuffer(m_trust, m_albedoTrust ? pixelCount(wp / 2, hp / 2) : 0, p, st);
    allocateBuffer(m_colorTaScaled, m_albedoTrust ? 3 * pixelCount(wp, hp) : 0, p, st);
    if (storesFused()) {
        allocateBuffer(m_fused, 3 * pixelCount(wp, hp), p, st);
        m_refineInput.allocate(wp, hp, kRefineInputChannels, p, st);
    } else {
        m_fused.release();
        m_refineInput = Tensor {};
    }
    if (refines()) {
        m_r1.allocate(wp, hp, channels(NetLayer::Ref1), p, st);
        m_r2.allocate(wp, hp, channels(NetLayer::Ref2), p, st);
    } else {
        m_r1 = Tensor {};
        m_r2 = Tensor {};
    }
    const std::size_t quarter = m_quarter ? pixelCount(wp / 4, hp / 4) : 0;
    allocateBuffer(m_quarterHalf, 12 * quarter, p, st); // D(i): 3 floats at half the size
    allocateBuffer(m_quarterLow, 3 * quarter, p, st);
    allocateBuffer(m_quarterLogits, m_head4.packed.outChannels * quarter, p, st);
    allocateBuffer(m_quarterDelta, 3 * quarter, p, st);
    m_layout = layout;
}

void AfnPipeline::configure(const Frame& frame)
{
    if (!m_hasNetwork)
        throwInvalidOperation("CUDA afn: no network loaded");
    useGpu(m_gpu);
    const FrameLayout layout = FrameLayout::of(frame);
    if (layout != m_layout) {
        allocate(layout);
        m_graphsValid = false;
    }
    if (!m_graphsValid)
        captureGraphs();
}

void AfnPipeline::captureGraphs()
{
    m_graphsValid = false;
    for (int slot = 0; slot < 2; ++slot)
        m_graphs[slot].reset(captureGraph(m_stream.get(), [&](cudaStream_t s) {
            enqueueFirstStage(slot, s);
            enqueueNetwork(slot, s);
            enqueueTaa(slot, s);
            enqueuePostFilter(slot, s);
        }));
    m_graphsValid = true;
}

void AfnPipeline::enqueue(Stage stage, cudaStream_t stream) const
{
    switch (stage) {
    case Stage::TemporalFeatures:
        return enqueueTemporalFeatures(m_slot, stream);
    case Stage::KernelPrediction:
        return enqueueKernelPrediction(networkSources(m_slot), stream);
    case Stage::FilteringFusion:
        return enqueueFilteringFusion(networkSources(m_slot), finalOutput(m_slot), stream);
    case Stage::Refinement:
        return enqueueRefinement(finalOutput(m_slot), stream);
    case Stage::Taa:
        return enqueueTaa(m_slot, stream);
    case Stage::PostFilter:
        return enqueuePostFilter(m_slot, stream);
    }
}

void AfnPipeline::setOption(bool& option, bool on)
{
    if (on == option)
        return;
    option = on;
    m_layout = FrameLayout {}; // buffers and graphs again at the next frame
    m_graphsValid = false;
}

void AfnPipeline::setNetworkInputs(const afnet::InputSet& inputs)
{
    if (inputs == m_networkInputs)
        return;
    m_networkInputs = inputs;
    m_layout = FrameLayout {}; // other sources (and buffers): allocate and capture again
    m_graphsValid = false;
}

void AfnPipeline::upload(const Frame& f, const FrameConstants& constants)
{
    useGpu(m_gpu);
    if (FrameLayout::of(f) != m_layout || !m_graphsValid)
        throwInvalidOperation("CUDA afn: upload of a frame the pipeline is not configured for");
    const cudaStream_t s = m_stream.get();
    const std::size_t n = pixelCount(f.width, f.height);
    uploadImage(m_color, f.color, 3 * n, s);
    if (m_layout.albedo)
        uploadImage(m_albedoRaw, f.albedo, 3 * n, s);
    if (m_layout.motion)
        uploadImage(m_motion, f.motion, 2 * n, s);
    if (m_layout.position)
        uploadImage(m_position[m_slot], f.position, 3 * n, s);
    if (m_layout.normal)
        uploadImage(m_normalRaw, f.normal, 3 * n, s);
    if (m_layout.depth)
        uploadImage(m_depthRaw, f.depth, n, s);
    // The TAA's history holds the previous frame's output only when the TAA ran then (as the CPU's
    // afn_method: a frame without TAA drops it).
    m_frameConstants = constants;
    m_frameConstants.taaHistory = m_taa && m_taaRan && constants.hasHistory ? 1 : 0;
    m_taaRan = m_taa;
    AFN_CUDA_CHECK(cudaMemcpyAsync(
        m_constants.data(), &m_frameConstants, sizeof(FrameConstants), cudaMemcpyHostToDevice, s));
    // Work skipping as the CPU's (afn_method.cpp, Network::run): in the balanced tier the rows
    // of the 8-row blocks near no work take the cheap path; the TAA's and the post-filter's
    // margins grow the needed rows.
    m_hostComputedRows.assign(static_cast<std::size_t>(f.height), 1);
    if (f.hasWorkMask() && skipsRows())
        m_hostComputedRows = afnet::computedRows(
            f.work, afnet::workMargin(m_taa, m_postFilter), f.height, m_grownWork);
    AFN_CUDA_CHECK(cudaMemcpyAsync(m_computedRows.data(), m_hostComputedRows.data(),
        m_computedRows.bytes(), cudaMemcpyHostToDevice, s));
    AFN_CUDA_CHECK(cudaStreamSynchronize(s)); // the host rows are rewritten next frame
    if (m_poison)
        AFN_CUDA_CHECK(cudaMemsetAsync(m_output.data(), 0xff, m_output.bytes(), s));
}

void AfnPipeline::launch()
{
    useGpu(m_gpu);
    AFN_CUDA_CHECK(cudaGraphLaunch(m_graphs[m_slot].get(), m_stream.get()));
}

void AfnPipeline::download(Image& out)
{
    useGpu(m_gpu);
    out.resize(m_layout.width, m_layout.height, 3);
    AFN_CUDA_CHECK(cudaMemcpyAsync(
        out.data(), m_output.data(), m_output.bytes(), cudaMemcpyDeviceToHost, m_stream.get()));
    AFN_CUDA_CHECK(cudaMemcpyAsync(&m_lastCutPixels, m_cutPixels.data(), m_cutPixels.bytes(),
        cudaMemcpyDeviceToHost, m_stream.get()));
    AFN_CUDA_CHECK(cudaMemcpyAsync(&m_lastAuxState, m_auxState.data(), m_auxState.bytes(),
        cudaMemcpyDeviceToHost, m_stream.get()));
    AFN_CUDA_CHECK(cudaStreamSynchronize(m_stream.get()));
    const double pixels = static_cast<double>(m_layout.width) * m_layout.height;
    m_lastCutShare = m_lastCutPixels / pixels;
    m_lastAux = auxReport(m_lastAuxState, m_layout, pixels);
}

void AfnPipeline::run(const Frame& frame, const FrameConstants& constants, Image& out)
{
    configure(frame);
    upload(frame, constants);
    launch();
    download(out);
    m_lastSlot = m_slot;
    advance();
}

std::size_t AfnPipeline::uploadBytes() const
{
    const FrameLayout& l = m_layout;
    const std::size_t floatsPerPixel = 3 + (l.albedo ? 3 : 0) + (l.motion ? 2 : 0)
        + (l.position ? 3 : 0) + (l.normal ? 3 : 0) + (l.depth ? 1 : 0);
    return pixelCount(l.width, l.height) * floatsPerPixel * sizeof(float) + sizeof(FrameConstants);
}

std::size_t AfnPipeline::downloadBytes() const
{
    return m_output.bytes() + m_cutPixels.bytes() + m_auxState.bytes();
}

void AfnPipeline::downloadIntermediate(Intermediate which, Image& out)
{
    useGpu(m_gpu);
    AFN_CUDA_CHECK(cudaStreamSynchronize(m_stream.get()));
    auto floats = [&](const DeviceBuffer<float>& b, int w, int h, int c) {
        if (b.size() != pixelCount(w, h) * c)
            throwInvalidOperation("CUDA afn: that intermediate is not computed");
        out.resize(w, h, c);
        AFN_CUDA_CHECK(cudaMemcpyAsync(
            out.data(), b.data(), b.bytes(), cudaMemcpyDeviceToHost, m_stream.get()));
        AFN_CUDA_CHECK(cudaStreamSynchronize(m_stream.get()));
    };
    auto halves = [&](const Tensor& t, int c) {
        std::vector<std::uint16_t> h(t.data.size());
        AFN_CUDA_CHECK(cudaMemcpyAsync(
            h.data(), t.data.data(), t.data.bytes(), cudaMemcpyDeviceToHost, m_stream.get()));
        AFN_CUDA_CHECK(cudaStreamSynchronize(m_stream.get()));
        out.resize(t.width, t.height, c);
        for (std::size_t p = 0; p < pixelCount(t.width, t.height); ++p)
            for (int k = 0; k < c; ++k)
                out.data()[p * c + k] = halfToFloat(h[p * t.stride + k]);
    };
    const int w = m_layout.width, h = m_layout.height;
    switch (which) {
    case Intermediate::Irradiance:
        return floats(m_irradiance, w, h, 3);
    case Intermediate::Accumulated:
        return floats(m_accumulated[m_lastSlot], w, h, 3);
    case Intermediate::NetworkInput:
        if (large())
            return halves(m_large.input(), kLargeInputChannels);
        return halves(m_x, m_historyInput ? kHistoryInputChannels : kInputChannels);
    case Intermediate::DecoderOutput:
        return halves(m_d1, layer(NetLayer::Dec1).packed.outChannels);
    case Intermediate::Fused:
        return floats(large() ? m_large.fused() : m_fused, m_paddedWidth, m_paddedHeight, 3);
    case Intermediate::AlbedoTrust:
        return floats(m_trust, m_paddedWidth / 2, m_paddedHeight / 2, 1);
    }
}

} // namespace afn::cuda
