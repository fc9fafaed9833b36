// SPDX-License-Identifier: Apache-2.0
// The "afn" filter on a CUDA device. It derives from Filter with no CPU stages: the Filter base
// gathers and sanitises the inputs on the CPU, then the whole method (aux prefilter, demodulation,
// reprojection, history trust, temporal accumulation, features, network, remodulation) runs on
// the GPU (afn_pipeline.h). It has
// the CPU filter's parameters, weights and errors; its results match the CPU's within the
// half-precision tolerance of docs/gpu.md.
#pragma once

#include "base/device.h"
#include "cuda/afn_pipeline.h"
#include "filter/registry.h"
#include "methods/afn/model_set.h"
#include "stages/aux_prefilter.h"
#include "stages/history_trust.h"
#include "stages/temporal_accumulation.h"

#include <memory>

namespace afn::cuda {

class AfnCudaFilter final : public Filter {
public:
    AfnCudaFilter(const FilterType& type, int gpu);

    void setData(const std::string& name, const void* data, std::size_t size) override;
    /// Fill the GPU buffers with NaN when allocated and the output before each frame (tests).
    void setPoison(bool poison) { m_pipeline.setPoison(poison); }
    /// The GPU pipeline (tests read intermediates from it).
    AfnPipeline& pipeline() { return m_pipeline; }
    /// The history trust's cut share of the last frame, measured on the GPU.
    double lastHistoryCutShare() const override { return m_pipeline.lastCutShare(); }
    /// The aux prefilter's report of the last frame, measured on the GPU.
    const AuxReport& auxReport() const override { return m_pipeline.lastAuxReport(); }
    bool auxNoisy() const override { return m_pipeline.lastAuxReport().noisy; }
    bool auxGrainLimited() const override { return m_pipeline.lastAuxReport().grainLimited; }
    /// AFN_STAT_AFN_MODEL: the model that ran on the last frame, as the CPU filter says it, and
    /// the inputs the frame lacked (held at their neutral values: the GPU has only full-input
    /// models).
    bool stringStatistic(const std::string& name, std::string& value) const override;

private:
    void configure() override;
    void denoise(const Frame& in, Image& out) override;

    afnet::Network m_net; ///< validated archive, packed for the GPU when it changes
    bool m_networkChanged = false;
    /// The built-in models; without weights given (setData) the full-input one trained at the
    /// sample count nearest the `spp` parameter's runs (as the CPU filter chooses; AFN large is
    /// left out: no GPU graph for it).
    afnet::ModelSet m_embedded;
    const afnet::Model* m_chosen = nullptr;
    bool m_userWeights = false;
    ReprojectSettings m_reproject;
    AccumulationSettings m_accumulation;
    HistoryTrustSettings m_trust;
    AuxSettings m_aux;
    float m_taaAlpha = 0.7f; ///< afnet::Settings::taaAlpha
    std::string m_modelText; ///< stringStatistic(AFN_STAT_AFN_MODEL) of the last frame
    AfnPipeline m_pipeline;
};

/// Create the afn filter on a CUDA device (the registry's factory for that device type).
std::unique_ptr<Filter> createAfnCudaFilter(const FilterType& type, const Device& device);

} // namespace afn::cuda
