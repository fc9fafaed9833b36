// SPDX-License-Identifier: Apache-2.0
// "mrkp": multi-resolution kernel prediction as defined in the NBGD paper's supplement (the
// paper's MR-KP baseline). Per frame, after the shared stages (aux prefilter, demodulation, BMFR
// temporal accumulation; the same inputs as the afn method, so `afntool --features:method=mrkp`
// writes what the toolkit trains on): scale normal and depth, run the network (network.h,
// kernels.h) and remodulate (clamped to >= 0). It keeps no history of its own (the temporal
// accumulation is the shared stage's). Weights: the archive embedded at build time
// (weights/mrkp.afnw), or afnSetFilterData(filter, "weights", ...).
#include "base/exception.h"
#include "filter/quality.h"
#include "filter/registry.h"
#include "methods/mrkp/network.h"
#include "nn/weights.h"
#include "stages/demodulate.h"
#include "stages/feature_scaling.h" // the shared feature scaling (normal01, depth01)

#include <algorithm>

#ifdef AFN_HAS_MRKP_WEIGHTS
extern "C" const unsigned char mrkpEmbeddedWeights[];
extern "C" const unsigned long long mrkpEmbeddedWeights_size;
#endif

namespace afn::mrkp {

namespace {

class MrkpFilter final : public Filter {
public:
    explicit MrkpFilter(const FilterType& t)
        : Filter(t)
    {
#ifdef AFN_HAS_MRKP_WEIGHTS
        m_net.load(nn::WeightsArchive::parse(mrkpEmbeddedWeights,
            static_cast<std::size_t>(mrkpEmbeddedWeights_size), "embedded MR-KP weights"));
#endif
    }

    void setData(const std::string& name, const void* data, std::size_t size) override
    {
        if (name != AFN_DATA_WEIGHTS)
            Filter::setData(name, data, size);
        Network net; // only valid weights replace the current ones
        net.load(nn::WeightsArchive::parse(data, size, "weights set with afnSetFilterData"));
        m_net = std::move(net);
        markDirty();
        reset();
    }

private:
    void configure() override
    {
        if (outputBound() && !m_net.loaded())
            throwInvalidOperation("mrkp: no weights: this build embeds no trained MR-KP model; "
                                  "set an .afnw file with afnSetFilterData(filter, \"weights\", "
                                  "data, size) (afntool: --weights FILE)");
    }
    void denoise(const Frame& in, Image& out) override
    {
        reportProgress(0.1);
        m_albedo.resize(in.width, in.height, 3);
        if (in.hasAlbedo())
            std::copy(in.albedo.data(), in.albedo.data() + in.albedo.size(), m_albedo.data());
        else
            m_albedo.fill(1.0f);
        normalToUnitRange(in.normal, in.width, in.height, m_normal01);
        depthToUnitRange(in.depth, in.width, in.height, m_depth01);
        writeFeature("irradiance", irradiance());
        writeFeature("accumulated", accumulator().color());
        writeFeature("albedo", m_albedo);
        writeFeature("normal01", m_normal01);
        writeFeature("depth01", m_depth01);
        if (!outputBound())
            return; // only the network's inputs were asked for
        m_net.run({ &accumulator().color(), &m_albedo, &m_normal01, &m_depth01 }, m_result);
        reportProgress(0.95);
        remodulate(in, m_result, out);
    }

    Network m_net;
    Image m_albedo, m_normal01, m_depth01, m_result;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "mrkp";
    t.description = "multi-resolution kernel prediction (KPCN with level blending, the paper's "
                    "MR-KP baseline) on the TA-accumulated frame";
#ifdef AFN_HAS_MRKP_WEIGHTS
    t.ready = true;
#else
    t.ready = false;
#endif
    t.stages = { true, StageNeeds::Reproject::Bilinear, true };
    t.inputs = { { { AFN_IMAGE_NORMAL }, "network features" },
        { { AFN_IMAGE_DEPTH }, "network features" } };
    t.features = {
        { "irradiance", 3, "1-spp colour divided by max(albedo, 2^-10), linear HDR, >= 0" },
        { "accumulated", 3, "BMFR temporal accumulation of the irradiance (TA-1spp), linear HDR" },
        { "albedo", 3, "demodulation factor (the albedo after the aux prefilter), [0, 1]" },
        { "normal01", 3, "prefiltered shading normal * 0.5 + 0.5, [0, 1]" },
        { "depth01", 1, "prefiltered per-frame min-max depth, [0, 1]" },
    };
    // Quality tiers (filter/quality.h): the baseline is reproduced as its paper defines it, one
    // network; a cheaper or dearer variant would be another model.
    t.qualityHelp = std::string(kQualityOneLevel) + " (a paper baseline: one trained model)";
    t.create = factoryOf<MrkpFilter>();
    return t;
}

} // namespace afn::mrkp
