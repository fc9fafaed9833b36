// SPDX-License-Identifier: Apache-2.0
// AFN large (methods/afn/network_large.h) on one GPU: its packed layers, its tensors at a padded
// frame size, and its stages enqueued in stream order (also inside a graph capture):
//   prepare      x, c, D(c), D(D(c)) (largePrepare, down2)
//   prediction   the U-Net on D(x)
//   filtering    the heads (1x1 convolutions, float logits): K3 on d2, [K2, a2] on d1,
//                [K1, a1] on [U d1, x]; each scale's softmax and 5x5 filtering; o2 = Eq. 3 (f2, f3,
//                a2), i = Eq. 3 (f1, o2, a1)
//   refinement   two modules o <- o + R([T(o), albedo, normal01, depth01]); the first writes o at
//                the padded size, the second the caller's FinalOutput (remodulated, cropped)
// Every row is computed (the CPU's AFN large ignores the work mask), in every quality tier but
// high (AfnPipeline runs the passes). Same tensor names as the CPU's graph.
#pragma once

#include "cuda/device_layers.h"
#include "cuda/kernels.h"
#include "methods/afn/network_large.h"

#include <array>
#include <cstdint>

namespace afn::cuda {

class LargeGraph {
public:
    /// Pack and upload the layers on `stream` (synchronised before returning).
    void setNetwork(const afnet::LargeNetwork& network, cudaStream_t stream);
    /// Free the layers and tensors (another variant runs).
    void release();
    /// Allocate the tensors for a padded frame size.
    void allocate(int paddedWidth, int paddedHeight, bool poison, cudaStream_t stream);

    void enqueuePrepare(const LargeSources& src, cudaStream_t stream) const;
    void enqueuePrediction(cudaStream_t stream) const;
    void enqueueFilteringFusion(cudaStream_t stream) const;
    /// `out` as the AFN refinement's (FinalOutput; its `fused` is set here, no cheap path).
    void enqueueRefinement(const FinalOutput& out, cudaStream_t stream) const;

    /// The network input x (padded size, 10 channels in halves) and the fused i (padded size).
    const HalfTensor& input() const { return m_x; }
    const DeviceBuffer<float>& fused() const { return m_fused; }

private:
    using L = afnet::LargeNetwork::Layer;
    const DeviceLayer& layer(L l, int offset = 0) const
    {
        return m_layers[static_cast<int>(l) + offset];
    }

    std::array<DeviceLayer, afnet::LargeNetwork::kLayers> m_layers;
    int m_paddedWidth = 0, m_paddedHeight = 0;
    HalfTensor m_x, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3, m_d2, m_d1, m_refineInput, m_r1,
        m_r2;
    DeviceBuffer<float> m_c, m_cHalf, m_cQuarter; ///< the colour and its D, D(D)
    DeviceBuffer<float> m_h1, m_h2, m_h3; ///< the heads' logits (26, 26, 25 per pixel)
    DeviceBuffer<float> m_f2, m_f3; ///< the filtered coarser scales; f2 becomes o2 in place
    DeviceBuffer<float> m_fused; ///< f1, then i in place
    DeviceBuffer<float> m_refined; ///< o after the first refinement module
};

} // namespace afn::cuda
