// SPDX-License-Identifier: Apache-2.0
#include "cuda/afn_cuda_filter.h"

#include "base/exception.h"
#include "cuda/frame_constants.h"
#include "filter/quality.h"
#include "methods/afn/weights_source.h"
#include "stages/aux_prefilter.h"

namespace afn::cuda {

AfnCudaFilter::AfnCudaFilter(const FilterType& type, int gpu)
    : Filter(type, StageNeeds {})
    , m_models(afnet::ModelSet::embedded())
    , m_pipeline(gpu)
{
}

void AfnCudaFilter::setData(const std::string& name, const void* data, std::size_t size)
{
    if (name != AFN_DATA_WEIGHTS)
        Filter::setData(name, data, size);
    m_models = afnet::ModelSet::fromData(data, size); // only valid weights replace the current ones
    m_model = nullptr;
    markDirty();
    reset();
}

const afnet::Model& AfnCudaFilter::chooseModel(const afnet::InputSet& available)
{
    if (m_models.empty())
        afnet::throwNoWeights();
    if (const afnet::Model* m = m_models.choose(available, m_aux.spp))
        return *m;
    m_models.throwNoModelFor(available);
}

void AfnCudaFilter::useModel(const afnet::Model& model)
{
    if (&model != m_model) {
        m_pipeline.setNetwork(model.net);
        m_model = &model;
    }
    // The output TAA and the post-filter as the CPU's (afn_method.cpp).
    m_pipeline.setTaa(afnet::taaOn(m_settings, model.spp));
    m_pipeline.setPostFilter(afnet::postFilterOn(m_settings, model.spp));
}

void AfnCudaFilter::configure()
{
    if (anyFeatureBound())
        throw Exception(AFN_ERROR_UNSUPPORTED,
            "afn on a CUDA device writes no feature outputs; create the filter on the CPU "
            "device for them (afntool: --device cpu)");
    m_aux = auxBinding().read(params());
    m_settings = afnet::settingsBinding().read(params());
    // Quality tiers (methods/afn/quality_tiers.h).
    const QualitySettings::Tier tier = qualityBinding().read(params()).quality;
    m_pipeline.setFastTier(tier == QualitySettings::Tier::Fast);
    m_pipeline.setHighTier(tier == QualitySettings::Tier::High);
    // The same parameters as the CPU filter's stages (filter/filter.cpp commit()).
    m_reproject = reprojectBinding().read(params());
    m_accumulation = accumulationBinding().read(params());
    m_trust = historyTrustBinding().read(params());
    // The model for the bound inputs, as the CPU filter: a missing one fails the commit; denoise
    // chooses again from each frame's own inputs.
    if (!outputBound())
        return;
    afnet::InputSet bound;
    bound.albedo = imageBound(AFN_IMAGE_ALBEDO);
    bound.normal = imageBound(AFN_IMAGE_NORMAL);
    bound.depth = imageBound(AFN_IMAGE_DEPTH);
    bound.temporal
        = imageBound(AFN_IMAGE_MOTION) || (imageBound(AFN_IMAGE_POSITION) && cameraSet());
    const afnet::Model& model = chooseModel(bound);
    useModel(model);
    // The accumulation's minimum blend for this model, as the CPU filter (afn_method.cpp).
    m_accumulation.alphaMin
        = afnet::accumulationAlphaMin(m_settings, m_accumulation.alphaMin, model.spp);
}

bool AfnCudaFilter::stringStatistic(const std::string& name, std::string& value) const
{
    if (name != AFN_STAT_AFN_MODEL)
        return false;
    value = m_modelText;
    return true;
}

void AfnCudaFilter::denoise(const Frame& in, Image& out)
{
    reportProgress(0.1);
    const afnet::InputSet available = afnet::inputSetOf(in);
    const afnet::Model& model = chooseModel(available);
    useModel(model);
    m_modelText = afnet::describeChoice(available, model);
    m_pipeline.setNetworkInputs(afnet::inputsToUse(available, model));
    FrameConstants c = frameConstants(in, m_reproject, m_accumulation, m_trust, m_aux);
    c.taaAlpha = m_settings.taaAlpha;
    c.highlights = m_settings.highlights;
    m_pipeline.run(in, c, out);
    reportProgress(0.95);
}

std::unique_ptr<Filter> createAfnCudaFilter(const FilterType& type, const Device& device)
{
    return std::make_unique<AfnCudaFilter>(type, device.gpuOrdinal());
}

} // namespace afn::cuda
