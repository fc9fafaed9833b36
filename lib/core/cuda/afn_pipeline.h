// SPDX-License-Identifier: Apache-2.0
// The whole afn filter on one GPU for a sequence: the device buffers of a frame size, the packed
// network, and the per-frame work captured as CUDA graphs. Per frame (run()): upload the gathered
// inputs, replay the graph, download the radiance. The temporal history (geometry, accumulated
// colour, history length) lives in two slots that swap every frame; one graph is captured per
// slot, so no buffer is copied between frames. Everything per frame that is not a buffer pointer
// (history flag, cameras, settings) is uploaded as FrameConstants, so the graphs stay valid across
// frames and are captured again only when the frame size, the set of inputs, the colour convention
// or the network changes.
//
// Stages (kernels.h; afn_pipeline_stages.cpp): TemporalFeatures (aux prefilter, TA with the
// history trust, network input with history01 for weights with the history input),
// KernelPrediction (encoder-decoder; the albedo trust after its first level for weights with
// albedoTrust=1), FilteringFusion (heads, softmax, filtering, Eq. 3), Refinement (variant "full";
// the output divided by the albedo trust's scale, remodulated), Taa and PostFilter (when set).
// Weights of AFN large run its graph (large_graph.h) in the network's stages instead.
#pragma once

#include "base/image.h"
#include "cuda/device_layers.h"
#include "cuda/device_memory.h"
#include "cuda/kernels.h"
#include "cuda/large_graph.h"
#include "filter/frame.h"
#include "methods/afn/input_set.h"
#include "methods/afn/network.h"
#include "stages/aux_prefilter.h"

#include <array>
#include <cstdint>

namespace afn::cuda {

/// What a frame looks like to the graphs.
struct FrameLayout {
    int width = 0;
    int height = 0;
    bool albedo = false;
    bool normal = false;
    bool depth = false;
    bool position = false;
    bool motion = false;
    bool colorDemodulated = false;
    bool operator==(const FrameLayout& o) const;
    bool operator!=(const FrameLayout& o) const { return !(*this == o); }
    static FrameLayout of(const Frame& frame);
};

class AfnPipeline {
public:
    enum class Stage {
        TemporalFeatures,
        KernelPrediction,
        FilteringFusion,
        Refinement,
        Taa,
        PostFilter
    };
    enum class Intermediate {
        Irradiance,
        Accumulated,
        NetworkInput,
        DecoderOutput,
        Fused,
        AlbedoTrust
    };

    explicit AfnPipeline(int gpu);
    AfnPipeline(const AfnPipeline&) = delete;
    AfnPipeline& operator=(const AfnPipeline&) = delete;
    ~AfnPipeline();

    /// Pack and upload a loaded network (takes effect at the next frame).
    void setNetwork(const afnet::Network& network);
    /// Run afn's output TAA (stages/taa.h) and post-filter (methods/afn/post_filter.h) on the
    /// output from the next frame on.
    void setTaa(bool on) { setOption(m_taa, on); }
    void setPostFilter(bool on) { setOption(m_postFilter, on); }
    /// The quality tier fast (methods/afn/quality_tiers.h): the fused image as the output, no
    /// refinement (weights without one run as they are).
    void setFastTier(bool on) { setOption(m_fast, on); }
    /// The quality tier high (methods/afn/quality_tiers.h): the network on the frame and its three
    /// mirror images, the outputs mirrored back and averaged.
    void setHighTier(bool on) { setOption(m_high, on); }
    /// What of a frame the network reads: the input set of the model it runs (the CPU filter's
    /// choice, methods/afn/model_set.h), as methods/afn/network_inputs.cpp prepares it. Without
    /// `temporal` the network runs without its temporal branch (the TA input is this frame's
    /// colour, history01 is 1); a role left out is held at its neutral value (albedo 1, normal01
    /// 0.5, depth01 0); without `albedo` on a frame that has one, the network filters the colours
    /// times the albedo and its output is not remodulated. The other stages (aux prefilter, TA,
    /// TAA, post-filter) read the frame's inputs whatever the set, as on the CPU.
    void setNetworkInputs(const afnet::InputSet& inputs);
    /// Poison every device buffer with NaN when it is allocated and the output before every
    /// frame, so that a value nothing wrote shows up (tests).
    void setPoison(bool poison) { m_poison = poison; }

    /// Denoise one gathered frame into `out` (3 channels, frame size).
    void run(const Frame& frame, const FrameConstants& constants, Image& out);

    // The pieces of run(), for the benchmark.
    /// Allocate the buffers and capture the graphs for this frame's layout (when changed).
    void configure(const Frame& frame);
    /// Copy the frame's inputs and constants into the current slot.
    void upload(const Frame& frame, const FrameConstants& constants);
    /// Replay the current slot's graph.
    void launch();
    /// Copy the output into `out` and wait for the stream (reports errors of the frame's work).
    void download(Image& out);
    /// The next frame uses the other slot.
    void advance() { m_slot ^= 1; }
    /// Enqueue one stage for the current slot (also inside a graph capture).
    void enqueue(Stage stage, cudaStream_t stream) const;
    cudaStream_t stream() const { return m_stream.get(); }
    /// Share of the last downloaded frame's pixels whose history the trust cut
    /// (HistoryTrust::cutShare()).
    double lastCutShare() const { return m_lastCutShare; }
    /// What the aux prefilter measured and decided for the last downloaded frame.
    const AuxReport& lastAuxReport() const { return m_lastAux; }
    /// Bytes uploaded and downloaded per frame with the configured layout.
    std::size_t uploadBytes() const;
    std::size_t downloadBytes() const;

    /// An intermediate of the last frame, as floats (tests). Irradiance, Accumulated: frame size,
    /// 3 ch; NetworkInput: padded size, 13 ch (14 with the history input; AFN large: its 10);
    /// DecoderOutput: half the padded size (not AFN large); Fused: padded size, 3 ch (variant
    /// "full", and AFN large's i); AlbedoTrust: half the padded size, 1 ch (weights with the
    /// albedo trust only). Call after run().
    void downloadIntermediate(Intermediate which, Image& out);

private:
    using Layer = DeviceLayer;
    using Tensor = HalfTensor;
    using NetLayer = afnet::Network::Layer;
    const Layer& layer(NetLayer l) const { return m_layers[static_cast<int>(l)]; }
    void allocate(const FrameLayout& layout);
    void captureGraphs();
    ConvOperands operands(const Layer& layer, const Tensor* up, const Tensor& same) const
    {
        return convOperands(layer, up, same);
    }
    FinalOutput finalOutput(int slot) const;
    /// What the network reads of a frame (frame size): the slot's buffers, or their mirror
    /// images for a pass of the quality tier high.
    struct NetworkSources {
        const float* color1 = nullptr;
        const float* colorTa = nullptr;
        const float* albedo = nullptr;
        const float* normal = nullptr;
        const float* depth = nullptr;
        const float* historyLength = nullptr;
    };
    /// The network's sources, its colours clamped by the highlight bypass (enqueueFirstStage).
    NetworkSources networkSources(int slot) const;
    /// The same with the colours as the first stage left them.
    NetworkSources givenSources(int slot) const;
    /// The colour the highlight bypass's limit and excess come from (NetworkInputs::colorTa).
    const float* highlightSource(int slot) const;
    /// Add the highlight bypass's excess to the output (before the TAA, or after the
    /// post-filter when it runs: afn_method.cpp).
    void enqueueHighlightExcess(int slot, cudaStream_t stream) const;
    void enqueueTemporalFeatures(int slot, cudaStream_t stream) const;
    void enqueueFirstStage(int slot, cudaStream_t stream) const; ///< aux prefilter, TA
    void enqueuePrepare(const NetworkSources& src, cudaStream_t stream) const;
    void enqueueKernelPrediction(const NetworkSources& src, cudaStream_t stream) const;
    void enqueueFilteringFusion(
        const NetworkSources& src, const FinalOutput& out, cudaStream_t stream) const;
    void enqueueRefinement(const FinalOutput& out, cudaStream_t stream) const;
    /// The network from the input preparation to the output: once, or the high tier's passes.
    void enqueueNetwork(int slot, cudaStream_t stream) const;
    /// Set an option that changes the buffers or graphs (reallocated and captured at the next
    /// frame when it changes).
    void setOption(bool& option, bool on);
    void enqueueTaa(int slot, cudaStream_t stream) const;
    void enqueuePostFilter(int slot, cudaStream_t stream) const;
    TemporalBuffers temporalBuffers(int slot) const;
    TrustBuffers trustBuffers() const;
    /// The network filters the colours times the albedo (setNetworkInputs()).
    bool undemodulates(const FrameLayout& layout) const
    {
        return layout.albedo && !m_networkInputs.albedo;
    }

    int m_gpu;
    Stream m_stream;
    bool m_poison = false;
    bool m_hasNetwork = false;
    bool m_refine = false; ///< the weights have a refinement (variant full)
    bool m_fast = false; ///< setFastTier()
    bool m_high = false; ///< setHighTier()
    afnet::InputSet m_networkInputs = afnet::InputSet::full(); ///< setNetworkInputs()
    /// The refinement runs this frame.
    bool refines() const { return m_refine && !m_fast; }
    /// Work skipping applies (the tiers fast, where it skips the refinement, and high compute
    /// every pixel, as AFN large does, as on the CPU: quality_tiers.h, network_large.h).
    bool skipsRows() const { return !(m_fast && m_refine) && !m_high && !large() && !m_quarter; }
    /// The weights are AFN large (m_large runs instead of the AFN graph; every row computed, the
    /// tier fast as balanced, as the CPU's Network).
    bool large() const { return m_variant == afnet::Variant::Large; }
    bool m_historyInput = false; ///< the network reads history01 (Network::hasHistoryInput)
    bool m_albedoTrust = false; ///< Network::hasAlbedoTrust
    bool m_quarter = false; ///< Network::hasQuarterScale (every row computed, as on the CPU)
    /// The fused image is stored (for the refinement, or for the quarter scale to correct it).
    bool storesFused() const { return refines() || m_quarter; }
    void enqueueQuarterScale(const FinalOutput& out, cudaStream_t stream) const;
    bool m_taa = false; ///< setTaa()
    bool m_postFilter = false; ///< setPostFilter()
    afnet::Variant m_variant = afnet::Variant::Full;
    std::array<Layer, 10> m_layers; ///< in Network::Layer order
    DeviceBuffer<float> m_trustHead; ///< packTrustHead() of headG (albedo trust only)
    FrameLayout m_layout; ///< of the allocated buffers and captured graphs
    bool m_graphsValid = false;
    int m_slot = 0; ///< slot of the current frame; the previous frame's is 1 - m_slot
    int m_lastSlot = 0; ///< slot of the last frame run()
    std::array<GraphExec, 2> m_graphs;

    // Frame-size buffers (floats, interleaved).
    DeviceBuffer<float> m_color, m_albedo, m_motion, m_irradiance, m_output;
    std::array<DeviceBuffer<float>, 2> m_position, m_normal, m_depth, m_accumulated, m_history;
    /// The 1-spp and TA colours times the albedo (undemodulates() only).
    std::array<DeviceBuffer<float>, 2> m_radianceInputs;
    /// The highlight bypass (highlight_pixel.h): the network's two colours clamped, the
    /// histogram and the limit.
    std::array<DeviceBuffer<float>, 2> m_highlightClamped;
    DeviceBuffer<unsigned> m_highlightCounts;
    DeviceBuffer<float> m_highlightLimit;
    DeviceBuffer<std::uint32_t> m_depthRange;
    // The history trust (history_trust_block.h): per row block sums, per block raw trust, count
    // and trust, the cut pixels (one word, copied back with the output).
    DeviceBuffer<float> m_trustRowSums, m_trustRaw, m_trustCount, m_trustBlock;
    // Work skipping: per frame row, 1 where the network's output is used (work_rows.h).
    DeviceBuffer<unsigned char> m_computedRows;
    std::vector<char> m_hostComputedRows; ///< this frame's, uploaded
    FrameConstants m_frameConstants; ///< this frame's, uploaded
    bool m_taaRan = false; ///< the last uploaded frame ran the TAA
    Image m_grownWork; ///< the work mask's rows grown by the TAA's and post-filter's margins
    DeviceBuffer<unsigned> m_cutPixels;
    // The aux prefilter (aux_prefilter_pixel.h): the albedo, normal and depth as uploaded (the
    // frame-size m_albedo, m_normal and m_depth hold them after the prefilter), the speckle flags
    // and discontinuity shares, the aux history per slot and the state (copied back with the
    // output for the report).
    DeviceBuffer<float> m_albedoRaw, m_normalRaw, m_depthRaw;
    std::array<DeviceBuffer<float>, 3> m_auxFlags;
    std::array<DeviceBuffer<float>, 2> m_auxEdges, m_auxHistory;
    DeviceBuffer<AuxState> m_auxState;
    // The post-filter's guide planes (a0 a1 a2 n0 n1 n2 nv z ls, frame size each) and its two
    // colour buffers.
    DeviceBuffer<float> m_postPlanes, m_postScratch0, m_postScratch1;
    std::array<DeviceBuffer<float>, 2> m_taaHistory; ///< the TAA's output per slot
    // The quality tier high: the mirrored network inputs (NetworkSources' order), a pass's
    // demodulated output and the passes' sum.
    std::array<DeviceBuffer<float>, 6> m_flipped;
    DeviceBuffer<float> m_passOut, m_passSum;
    AuxState m_lastAuxState {};
    AuxReport m_lastAux;
    unsigned m_lastCutPixels = 0;
    double m_lastCutShare = 0.0;
    DeviceBuffer<FrameConstants> m_constants;
    // Network tensors (padded frame and its levels).
    int m_paddedWidth = 0, m_paddedHeight = 0;
    Tensor m_x, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3, m_d2, m_d1, m_refineInput, m_r1,
        m_r2;
    DeviceBuffer<float> m_color1Half, m_fused;
    // The albedo trust's t (half the padded frame) and the TA colour times s (padded frame).
    DeviceBuffer<float> m_trust, m_colorTaScaled;
    LargeGraph m_large; ///< AFN large's layers and tensors (weights with variant=large)
    // The quarter scale (quarter_pixel.h): head4, D(i), l = D(D(i)), head4's logits, the delta.
    Layer m_head4;
    DeviceBuffer<float> m_quarterHalf, m_quarterLow, m_quarterLogits, m_quarterDelta;
};

} // namespace afn::cuda
