// SPDX-License-Identifier: Apache-2.0
// "wskpn": the weight-sharing kernel-prediction denoiser (Fan et al. 2021), one of the paper's
// learned baselines. Per frame, after the shared stages (aux prefilter, demodulation, BMFR
// temporal accumulation: the same TA-1spp colour afn reads): the 10-channel input
// (nn/baseline_input.h), the folded network and the weight-sharing filter (network.h), then
// remodulation by the albedo. Weights: the archive embedded at build time (weights/wskpn.afnw,
// trained with training/afn/baselines/train.py) or afnSetFilterData(filter, "weights", ...).
#include "base/exception.h"
#include "filter/quality.h"
#include "filter/registry.h"
#include "methods/wskpn/network.h"
#include "nn/baseline_input.h"
#include "stages/demodulate.h"

#ifdef AFN_HAS_EMBEDDED_WSKPN_WEIGHTS
extern "C" const unsigned char wskpnEmbeddedWeights[];
extern "C" const unsigned long long wskpnEmbeddedWeights_size;
#endif

namespace afn::wskpn {

namespace {

class WskpnFilter final : public Filter {
public:
    explicit WskpnFilter(const FilterType& t)
        : Filter(t)
    {
#ifdef AFN_HAS_EMBEDDED_WSKPN_WEIGHTS
        m_net.load(nn::WeightsArchive::parse(wskpnEmbeddedWeights,
            static_cast<std::size_t>(wskpnEmbeddedWeights_size), "embedded WSKPN weights"));
#endif
    }

    void setData(const std::string& name, const void* data, std::size_t size) override
    {
        if (name != AFN_DATA_WEIGHTS)
            Filter::setData(name, data, size);
        Network net;
        net.load(nn::WeightsArchive::parse(data, size, "weights set with afnSetFilterData"));
        m_net = std::move(net); // only valid weights replace the current ones
        markDirty();
        reset();
    }

    bool statistic(const std::string& name, double& value) const override
    {
        if (name != "stats.wskpn.gflop")
            return false;
        value = m_net.flopPerPixel() * m_pixels * 1e-9;
        return true;
    }

private:
    void configure() override
    {
        if (outputBound() && !m_net.loaded())
            throwInvalidOperation(
                "wskpn: no weights: this build embeds no trained WSKPN model; set "
                "an .afnw file with afnSetFilterData(filter, \"weights\", data, "
                "size) (afntool: --weights FILE)");
    }

    void denoise(const Frame& in, Image& out) override
    {
        reportProgress(0.1);
        m_features.compute(in);
        writeFeature("accumulated", accumulator().color());
        writeFeature("albedo", m_features.albedo);
        writeFeature("normal01", m_features.normal01);
        writeFeature("depth01", m_features.depth01);
        if (!outputBound())
            return;
        m_pixels = static_cast<double>(in.width) * in.height;
        nn::baselineInput(accumulator().color(), m_features, m_input);
        m_net.run(m_input, accumulator().color(), m_result);
        reportProgress(0.95);
        remodulate(in, m_result, out);
    }

    Network m_net;
    nn::BaselineFeatures m_features;
    Image m_input, m_result;
    double m_pixels = 0;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "wskpn";
    t.description = "Weight-sharing kernel prediction (Fan et al. 2021): learned per-pixel weights "
                    "shared over six box windows on the temporal accumulation";
#ifdef AFN_HAS_EMBEDDED_WSKPN_WEIGHTS
    t.ready = true;
#else
    t.ready = false;
#endif
    t.stages = { true, StageNeeds::Reproject::Bilinear, true };
    t.inputs = { { { AFN_IMAGE_NORMAL }, "network features" },
        { { AFN_IMAGE_DEPTH }, "network features" } };
    t.features = {
        { "accumulated", 3, "BMFR temporal accumulation of the irradiance (TA-1spp), linear HDR" },
        { "albedo", 3, "demodulation factor (the albedo after the aux prefilter), [0, 1]" },
        { "normal01", 3, "prefiltered shading normal * 0.5 + 0.5, [0, 1]" },
        { "depth01", 1, "prefiltered per-frame min-max depth, [0, 1]" },
    };
    // Quality tiers (filter/quality.h): the baseline is reproduced as its paper defines it, one
    // network and one filter; a cheaper or dearer variant would be another model.
    t.qualityHelp = std::string(kQualityOneLevel) + " (a paper baseline: one trained model)";
    t.create = factoryOf<WskpnFilter>();
    return t;
}

} // namespace afn::wskpn
