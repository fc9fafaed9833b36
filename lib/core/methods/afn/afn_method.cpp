// SPDX-License-Identifier: Apache-2.0
// "afn": the Adaptive Fusion Network denoiser (Lee et al.). Per frame, after the shared stages
// (demodulation of the 1-spp colour, BMFR temporal accumulation for TA-1spp): scale normal and
// depth (features.h), run the network (network.h) and remodulate. The network output is clamped
// to >= 0 by the remodulation (stages/demodulate.h).
//
// Weights: the shipped archive embedded at build time (cmake/AfnEmbed.cmake, AFN_WEIGHTS_FILE)
// when the build has one, else none; afnSetFilterData(filter, AFN_DATA_WEIGHTS, data, size)
// overrides at run time. Without weights commit fails with a message: untrained weights never run
// silently.
#include "base/exception.h"
#include "filter/registry.h"
#include "methods/afn/features.h"
#include "methods/afn/network.h"
#include "stages/demodulate.h"

#include <algorithm>

#ifdef AFN_HAS_EMBEDDED_WEIGHTS
extern "C" const unsigned char afnEmbeddedWeights[];
extern "C" const unsigned long long afnEmbeddedWeights_size;
#endif

namespace afn::afnet {

namespace {

class AfnFilter final : public Filter {
public:
    explicit AfnFilter(const FilterType& t)
        : Filter(t)
    {
#ifdef AFN_HAS_EMBEDDED_WEIGHTS
        m_net.load(nn::WeightsArchive::parse(afnEmbeddedWeights,
            static_cast<std::size_t>(afnEmbeddedWeights_size), "embedded AFN weights"));
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

private:
    void configure() override
    {
        if (outputBound() && !m_net.loaded())
            throwInvalidOperation(
                "afn: no weights: this build embeds no trained AFN model; set an .afnw file "
                "with afnSetFilterData(filter, \"weights\", data, size) (afntool: --weights FILE)");
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
        const Inputs net { &irradiance(), &accumulator().color(), &m_albedo, &m_normal01,
            &m_depth01 };
        m_net.run(net, m_result);
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
    t.name = "afn";
    t.description = "Adaptive Fusion Network (Lee et al.): kernel-predicting network fusing the "
                    "1-spp frame and its BMFR temporal accumulation";
#ifdef AFN_HAS_EMBEDDED_WEIGHTS
    t.ready = true;
#else
    t.ready = false;
#endif
    t.stages = { true, StageNeeds::Reproject::Bilinear, true };
    t.features = {
        { "irradiance", 3, "1-spp colour divided by max(albedo, 2^-10), linear HDR, >= 0" },
        { "accumulated", 3, "BMFR temporal accumulation of the irradiance (TA-1spp), linear HDR" },
        { "albedo", 3, "albedo as the network sees it, [0, 1] (1 without an albedo input)" },
        { "normal01", 3, "shading normal * 0.5 + 0.5, [0, 1] (0.5 without a normal input)" },
        { "depth01", 1, "per-frame min-max depth, [0, 1] (0 without a depth input)" },
    };
    t.create = factoryOf<AfnFilter>();
    return t;
}

} // namespace afn::afnet
