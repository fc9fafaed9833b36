// SPDX-License-Identifier: Apache-2.0
#include "cuda/afn_cuda_filter.h"

#include "base/exception.h"
#include "cuda/frame_constants.h"
#include "filter/quality.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"
#include "stages/aux_prefilter.h"

namespace afn::cuda {

AfnCudaFilter::AfnCudaFilter(const FilterType& type, int gpu)
    : Filter(type, StageNeeds {})
    , m_embedded(afnet::ModelSet::embedded())
    , m_pipeline(gpu)
{
}

void AfnCudaFilter::setData(const std::string& name, const void* data, std::size_t size)
{
    if (name != AFN_DATA_WEIGHTS)
        Filter::setData(name, data, size);
    m_net = afnet::networkFromData(data, size); // only valid weights replace the current ones
    m_networkChanged = true;
    m_userWeights = true;
    markDirty();
    reset();
}

void AfnCudaFilter::configure()
{
    if (anyFeatureBound())
        throw Exception(AFN_ERROR_UNSUPPORTED,
            "afn on a CUDA device writes no feature outputs; create the filter on the CPU "
            "device for them (afntool: --device cpu)");
    m_aux = auxBinding().read(params());
    if (!m_userWeights) {
        const afnet::Model* m = m_embedded.choose(afnet::InputSet::full(), m_aux.spp, false);
        if (m && m != m_chosen) {
            m_chosen = m;
            m_net = m->net;
            m_networkChanged = true;
        }
    }
    if (!m_net.loaded())
        afnet::throwNoWeights();
    if (m_net.variant() == afnet::Variant::Large) // no GPU graph for it yet
        throw Exception(AFN_ERROR_UNSUPPORTED,
            "afn on a CUDA device has no AFN large graph yet: weights with variant=large run on "
            "the CPU device (afntool: --device cpu)");
    if (m_net.hasQuarterScale()) // no GPU graph for it yet
        throw Exception(AFN_ERROR_UNSUPPORTED,
            "afn on a CUDA device has no quarter-resolution scale yet: weights with quarter=1 "
            "run on the CPU device (afntool: --device cpu)");
    // Quality tiers (methods/afn/quality_tiers.h).
    const QualitySettings::Tier tier = qualityBinding().read(params()).quality;
    m_pipeline.setFastTier(tier == QualitySettings::Tier::Fast);
    m_pipeline.setHighTier(tier == QualitySettings::Tier::High);
    // The output TAA and the post-filter as the CPU's (afn_method.cpp): auto is on for weights
    // trained below 16 spp.
    const afnet::Settings settings = afnet::settingsBinding().read(params());
    const bool lowSpp = m_net.trainedSpp() < afnet::kTaaAutoMaxSppExclusive;
    m_pipeline.setTaa(settings.taa == afnet::Settings::Taa::On
        || (settings.taa == afnet::Settings::Taa::Auto && lowSpp));
    m_taaAlpha = settings.taaAlpha;
    const afnet::Settings::PostFilter post = settings.postFilter;
    m_pipeline.setPostFilter(post == afnet::Settings::PostFilter::On
        || (post == afnet::Settings::PostFilter::Auto
            && m_net.trainedSpp() < afnet::kPostFilterAutoMaxSppExclusive));
    // The same parameters as the CPU filter's stages (filter/filter.cpp commit()).
    m_reproject = reprojectBinding().read(params());
    m_accumulation = accumulationBinding().read(params());
    m_trust = historyTrustBinding().read(params());
    if (m_networkChanged) {
        m_pipeline.setNetwork(m_net);
        m_networkChanged = false;
    }
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
    const afnet::InputSet available { in.hasAlbedo(), in.hasNormal(), in.hasDepth(),
        in.hasMotion() || (in.hasPosition() && in.camera.valid) };
    const afnet::InputSet missing { !available.albedo, !available.normal, !available.depth, false };
    m_modelText = m_chosen ? afnet::describeChoice(afnet::InputSet::full(), *m_chosen)
                           : "model given with afnSetFilterData";
    if (missing.count() > 0)
        m_modelText += "; absent, held at neutral values: " + afnet::inputSetKey(missing);
    if (!available.temporal)
        m_modelText += "; no motion or position: run without its temporal branch";
    m_pipeline.setTemporalInputs(available.temporal);
    FrameConstants c = frameConstants(in, m_reproject, m_accumulation, m_trust, m_aux);
    c.taaAlpha = m_taaAlpha;
    m_pipeline.run(in, c, out);
    reportProgress(0.95);
}

std::unique_ptr<Filter> createAfnCudaFilter(const FilterType& type, const Device& device)
{
    return std::make_unique<AfnCudaFilter>(type, device.gpuOrdinal());
}

} // namespace afn::cuda
