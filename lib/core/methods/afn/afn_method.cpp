// SPDX-License-Identifier: Apache-2.0
// "afn": the Adaptive Fusion Network denoiser (Lee et al.). Per frame: demodulate the 1-spp colour,
// run BMFR temporal accumulation (the same Reprojector/TemporalAccumulator as "ta") for TA-1spp,
// scale normal and depth (afn_features.h), run the network (afn_network.h) and remodulate.
// The network output is clamped to >= 0 by the remodulation (demodulate.h).
//
// Weights: the shipped archive embedded at build time (cmake/AfnEmbed.cmake, AFN_WEIGHTS_FILE)
// when the build has one, else none; afnSetFilterData(filter, "weights", data, size) overrides at
// run time. Without weights commit fails with a message: untrained weights never run silently.
#include "methods/afn/features.h"
#include "methods/afn/network.h"
#include "stages/demodulate.h"
#include "base/exception.h"
#include "filter/registry.h"
#include "stages/temporal_accumulation.h"

#include <algorithm>

#ifdef AFN_HAS_EMBEDDED_WEIGHTS
extern "C" const unsigned char afnEmbeddedWeights[];
extern "C" const unsigned long long afnEmbeddedWeights_size;
#endif

namespace afn::afnet {

namespace {

class AfnFilter final : public Filter {
public:
    explicit AfnFilter(const std::vector<ParamDesc>* table)
        : Filter(table)
    {
#ifdef AFN_HAS_EMBEDDED_WEIGHTS
        m_net.load(nn::WeightsArchive::parse(afnEmbeddedWeights,
            static_cast<std::size_t>(afnEmbeddedWeights_size), "embedded AFN weights"));
#endif
    }

    void setData(const std::string& name, const void* data, std::size_t size) override
    {
        if (name != "weights")
            Filter::setData(name, data, size);
        Network net;
        net.load(nn::WeightsArchive::parse(data, size, "weights set with afnSetFilterData"));
        m_net = std::move(net); // only valid weights replace the current ones
        markDirty();
        resetHistory();
    }

private:
    void configure() override
    {
        if (!m_net.loaded())
            throwInvalidOperation(
                "afn: no weights: this build embeds no trained AFN model; set an .afnw file "
                "with afnSetFilterData(filter, \"weights\", data, size) (afntool: --weights FILE)");
        m_reproject.setSettings(readReprojectSettings(params()));
        m_ta.setAlphaMin(params().getFloat("alphaMin"));
    }
    void resetHistory() override
    {
        m_reproject.reset();
        m_ta.reset();
    }
    void denoise(const Frame& in, Image& out) override
    {
        if (in.frameIndex == 0)
            resetHistory();
        demodulate(in, m_irradiance);
        m_reproject.compute(in);
        m_ta.accumulate(m_reproject, m_irradiance);
        m_reproject.storeGeometry(in);
        reportProgress(0.1);
        if (in.hasAlbedo()) {
            m_albedo.resize(in.width, in.height, 3);
            std::copy(in.albedo.data(), in.albedo.data() + in.albedo.size(), m_albedo.data());
        } else {
            m_albedo.resize(in.width, in.height, 3);
            m_albedo.fill(1.0f);
        }
        normalToUnitRange(in.normal, in.width, in.height, m_normal01);
        depthToUnitRange(in.depth, in.width, in.height, m_depth01);
        const Inputs net { &m_irradiance, &m_ta.color(), &m_albedo, &m_normal01, &m_depth01 };
        m_net.run(net, m_result);
        reportProgress(0.95);
        remodulate(in, m_result, out);
    }

    Network m_net;
    Reprojector m_reproject;
    TemporalAccumulator m_ta;
    Image m_irradiance, m_albedo, m_normal01, m_depth01, m_result;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "afn";
    t.description = "Adaptive Fusion Network (Lee et al.): kernel-predicting network fusing the "
                    "1-spp frame and its BMFR temporal accumulation; "
#ifdef AFN_HAS_EMBEDDED_WEIGHTS
                    "this build embeds trained weights (the 'weights' data parameter overrides)";
#else
                    "needs trained weights: this build embeds none, set them with the 'weights' "
                    "data parameter";
#endif
#ifdef AFN_HAS_EMBEDDED_WEIGHTS
    t.ready = true;
#else
    t.ready = false;
#endif
    t.params = { floatParam("alphaMin", 0.2, 0.0, 1.0, "Minimum blend factor",
        "temporal accumulation of the TA-1spp input: weight of the current frame "
        "once the history is long (BMFR: 0.2)") };
    for (ParamDesc& d : reprojectParams())
        t.params.push_back(std::move(d));
    t.create = [](const std::vector<ParamDesc>* table) {
        return std::unique_ptr<Filter>(new AfnFilter(table));
    };
    return t;
}

} // namespace afn::afnet
