// SPDX-License-Identifier: Apache-2.0
// AFN large's graph on the CPU: cuda/large_graph.cpp's wiring (tensors, stage order) over the
// emulated kernels of cuda_emulator.h, run by EmulatedAfnPipeline for weights with variant=large.
#pragma once

#include "cuda_emulator.h"
#include "emulated_tensors.h"

#include "cuda/large_pixel.h"
#include "methods/afn/network_large.h"

#include <array>
#include <vector>

namespace afntest {

class EmulatedLargeGraph {
public:
    void setNetwork(const afn::afnet::LargeNetwork& network);
    void allocate(int paddedWidth, int paddedHeight);
    /// LargeGraph's stages in order: prepare, prediction, filtering and fusion, refinement.
    void run(const afn::cuda::LargeSources& src, const afn::cuda::FinalOutput& out);

    const HostTensor& input() const { return m_x; }
    const std::vector<float>& fused() const { return m_fused; }

private:
    using L = afn::afnet::LargeNetwork::Layer;
    const HostLayer& layer(L l, int offset = 0) const
    {
        return m_layers[static_cast<int>(l) + offset];
    }

    std::array<HostLayer, afn::afnet::LargeNetwork::kLayers> m_layers;
    int m_paddedWidth = 0, m_paddedHeight = 0;
    HostTensor m_x, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3, m_d2, m_d1, m_refineInput, m_r1,
        m_r2;
    std::vector<float> m_c, m_cHalf, m_cQuarter, m_h1, m_h2, m_h3, m_f2, m_f3, m_fused, m_refined;
};

} // namespace afntest
