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
#include "methods/afn/settings.h"
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
    /// AFN_STAT_AFN_MODEL: the model that ran on the last frame, as the CPU filter says it.
    bool stringStatistic(const std::string& name, std::string& value) const override;

protected:
    /// The model's training sample count, as the CPU filter (detail restoration's auto).
    int samplesMadeFor() const override { return m_model ? m_model->spp : 1; }

private:
    void configure() override;
    void denoise(const Frame& in, Image& out) override;

    /// The model for a frame with `available` inputs (the CPU filter's choice); throws as the
    /// CPU filter does when none is covered.
    const afnet::Model& chooseModel(const afnet::InputSet& available);
    /// Give the pipeline the model (packed and uploaded when it changes) and the settings that
    /// follow from its training sample count (the output TAA and the post-filter on auto).
    void useModel(const afnet::Model& model);

    /// The built-in models, or the one archive given with setData, as the CPU filter's: the
    /// model for each frame's inputs (model_set.h).
    afnet::ModelSet m_models;
    const afnet::Model* m_model = nullptr; ///< the model the pipeline has
    afnet::Settings m_settings;
    ReprojectSettings m_reproject;
    AccumulationSettings m_accumulation;
    HistoryTrustSettings m_trust;
    AuxSettings m_aux;
    std::string m_modelText; ///< stringStatistic(AFN_STAT_AFN_MODEL) of the last frame
    AfnPipeline m_pipeline;
};

/// Create the afn filter on a CUDA device (the registry's factory for that device type).
std::unique_ptr<Filter> createAfnCudaFilter(const FilterType& type, const Device& device);

} // namespace afn::cuda
