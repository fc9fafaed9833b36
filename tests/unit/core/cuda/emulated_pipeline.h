// SPDX-License-Identifier: Apache-2.0
// The whole CUDA afn filter run on the CPU: cuda/afn_pipeline.cpp's wiring (buffers, history
// slots, stage order) over the emulated kernels of cuda_emulator.h, so that its results are what
// the GPU computes up to the order of the tensor cores' float additions.
#pragma once

#include "cuda_emulator.h"
#include "emulated_large.h"
#include "emulated_tensors.h"

#include "base/image.h"
#include "cuda/frame_constants.h"
#include "filter/frame.h"
#include "methods/afn/input_set.h"
#include "methods/afn/network.h"

#include <array>
#include <cstdint>
#include <vector>

namespace afntest {

/// The whole CUDA afn filter on the CPU (cuda/afn_pipeline.cpp's wiring, host buffers).
class EmulatedAfnPipeline {
public:
    explicit EmulatedAfnPipeline(const afn::afnet::Network& network);
    /// Run the TAA and the post-filter on the output (AfnPipeline::setTaa, setPostFilter).
    void setTaa(bool on) { m_taa = on; }
    void setPostFilter(bool on) { m_postFilter = on; }
    /// The quality tiers fast (no refinement) and high (AfnPipeline::setFastTier, setHighTier).
    void setFastTier(bool on) { m_fast = on; }
    void setHighTier(bool on) { m_high = on; }
    /// AfnPipeline::setNetworkInputs.
    void setNetworkInputs(const afn::afnet::InputSet& inputs) { m_networkInputs = inputs; }
    /// Denoise a gathered frame (as AfnCudaFilter::denoise) into `out` (3 ch, frame size).
    void run(const afn::Frame& frame, const afn::cuda::FrameConstants& constants, afn::Image& out);

    // Intermediates of the last frame, as floats.
    const afn::Image& irradiance() const { return m_irradianceImage; }
    const afn::Image& accumulated() const { return m_accumulatedImage; }
    const afn::Image& historyLength() const { return m_historyLengthImage; }
    /// The history trust's cut share (HistoryTrust::cutShare()).
    double cutShare() const { return m_cutShare; }
    /// The albedo, normal and depth after the aux prefilter (frame size; empty where absent).
    const afn::Image& albedo() const { return m_albedoImage; }
    const afn::Image& normal() const { return m_normalImage; }
    const afn::Image& depth() const { return m_depthImage; }
    const afn::cuda::AuxState& auxState() const { return m_auxState; }
    /// The radiance before the TAA and the post-filter (frame size, 3 ch).
    const afn::Image& radiance() const { return m_radianceImage; }
    afn::Image networkInput() const; ///< padded size, 13 ch (14 with the history input)
    afn::Image decoderOutput() const; ///< half the padded size
    /// The albedo trust's t, half the padded size, 1 ch (weights with the albedo trust only).
    afn::Image albedoTrust() const;

private:
    using Tensor = HostTensor;
    using Layer = HostLayer;
    afn::cuda::ConvOperands operands(const Layer& layer, const Tensor* up, const Tensor& same) const
    {
        return hostOperands(layer, up, same);
    }
    void allocate(const afn::Frame& frame);
    /// AfnPipeline::NetworkSources: what the network reads of a frame.
    struct NetworkSources {
        const float *color1, *colorTa, *albedo, *normal, *depth, *historyLength;
    };
    /// The network from its input to `fo` (AfnPipeline's prepare, prediction, filtering and
    /// fusion, refinement).
    /// AfnPipeline::enqueueQuarterScale on m_fused.
    void emulateQuarterScale(bool refines, const afn::cuda::FinalOutput& fo);
    void runNetwork(
        const NetworkSources& src, const afn::cuda::FinalOutput& fo, const std::uint32_t* range);

    afn::afnet::Variant m_variant;
    bool m_refine;
    bool m_fast = false;
    bool m_high = false;
    afn::afnet::InputSet m_networkInputs = afn::afnet::InputSet::full();
    std::array<std::vector<float>, 2> m_radianceInputs; ///< AfnPipeline's, for undemodulates()
    std::array<std::vector<float>, 2> m_highlightClamped; ///< AfnPipeline's highlight bypass
    EmulatedLargeGraph m_large; ///< AFN large's graph (weights with variant=large)
    bool m_historyInput;
    bool m_albedoTrust;
    bool m_quarter; ///< Network::hasQuarterScale
    Layer m_head4; ///< its head
    bool m_taa = false;
    bool m_taaRan = false; ///< the last frame ran the TAA (AfnPipeline::upload)
    bool m_postFilter = false;
    std::array<std::vector<float>, 2> m_taaHistory;
    std::vector<float> m_postPlanes, m_postScratch0, m_postScratch1;
    std::vector<float> m_trustHead; ///< packTrustHead() (albedo trust only)
    std::array<Layer, 10> m_layers;
    int m_width = 0, m_height = 0, m_paddedWidth = 0, m_paddedHeight = 0;
    int m_slot = 0;
    std::vector<float> m_color, m_albedo, m_motion, m_irradiance, m_output, m_color1Half, m_fused;
    std::vector<float> m_trust, m_colorTaScaled;
    std::array<std::vector<float>, 2> m_position, m_normal, m_depth, m_accumulated, m_history;
    Tensor m_x, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3, m_d2, m_d1, m_refineInput, m_r1,
        m_r2;
    std::vector<float> m_trustRowSums, m_trustRaw, m_trustCount, m_trustBlock;
    std::vector<float> m_albedoRaw, m_normalRaw, m_depthRaw;
    std::array<std::vector<float>, 3> m_auxFlags;
    std::array<std::vector<float>, 2> m_auxEdges, m_auxHistory;
    afn::cuda::AuxState m_auxState {};
    afn::Image m_albedoImage, m_normalImage, m_depthImage, m_radianceImage;
    double m_cutShare = 0.0;
    afn::Image m_irradianceImage, m_accumulatedImage, m_historyLengthImage;
};

} // namespace afntest
