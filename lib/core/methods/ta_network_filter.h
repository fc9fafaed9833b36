// SPDX-License-Identifier: Apache-2.0
// The filter shared by the learned baselines that run one trained network on the shared stages'
// output (onnd, mrkp): after the aux prefilter, the demodulation and the BMFR temporal
// accumulation (the same inputs as the afn method, so `afntool --features:method=M` writes what
// the toolkit trains on), scale normal and depth, run the network on the TA-accumulated
// irradiance with albedo, normal and depth, and remodulate (clamped to >= 0).
//
// Weights: the archive embedded at build time (weights/<method>.afnw), or
// afnSetFilterData(filter, "weights", ...); only a valid archive replaces the current one.
// A network with a state of its own (onnd's recurrent state) drops it in resetHistory().
#pragma once

#include "base/exception.h"
#include "filter/quality.h"
#include "filter/registry.h"
#include "nn/weights.h"
#include "stages/demodulate.h"
#include "stages/feature_scaling.h" // the shared feature scaling (normal01, depth01)

#include <algorithm>
#include <string>
#include <vector>

namespace afn {

/// Names of one such method: the method's name ("mrkp") and its model's ("MR-KP").
struct TaNetworkNames {
    const char* method;
    const char* model;
};

/// The archive embedded at build time, or { nullptr, 0 } when the build has none.
struct EmbeddedWeights {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};

/// The FilterType fields every TA-network method shares: the stages (demodulation, bilinear
/// reprojection, temporal accumulation), the inputs, the feature outputs (the network's inputs,
/// `afntool --features:method=M`) and the quality help. The caller sets name, description,
/// ready and create.
inline void describeTaNetworkMethod(FilterType& t)
{
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
}

/// Network: load(const nn::WeightsArchive&), loaded(), and
/// run({ &accumulated, &albedo, &normal01, &depth01 }, Image& out).
template <class Network> class TaNetworkFilter : public Filter {
public:
    TaNetworkFilter(const FilterType& t, TaNetworkNames names, EmbeddedWeights embedded)
        : Filter(t)
        , m_names(names)
    {
        if (embedded.data)
            m_net.load(nn::WeightsArchive::parse(
                embedded.data, embedded.size, std::string("embedded ") + names.model + " weights"));
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

protected:
    Network m_net;

private:
    void configure() override
    {
        if (outputBound() && !m_net.loaded())
            throwInvalidOperation(std::string(m_names.method)
                + ": no weights: this build embeds no trained " + m_names.model
                + " model; set an .afnw file with afnSetFilterData(filter, \"weights\", data, "
                  "size) (afntool: --weights FILE)");
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

    TaNetworkNames m_names;
    Image m_albedo, m_normal01, m_depth01, m_result;
};

} // namespace afn
