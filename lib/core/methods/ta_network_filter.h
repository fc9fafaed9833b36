// SPDX-License-Identifier: Apache-2.0
// The filter shared by the learned baselines that run one trained network on the shared stages'
// output (onnd, mrkp): after the aux prefilter, the demodulation and the BMFR temporal
// accumulation (the same inputs as the afn method, so `afntool --features:method=M` writes what
// the toolkit trains on), scale normal and depth (nn::BaselineFeatures, as wskpn and nbgd), run
// the network on the TA-accumulated irradiance with albedo, normal and depth, and remodulate
// (clamped to >= 0). Unlike nn::BaselineFilter (wskpn, nbgd) the network takes the four images
// itself, and the 1-spp irradiance is a feature output too.
//
// Weights: the archive embedded at build time (weights/<method>.afnw), or
// afnSetFilterData(filter, "weights", ...); only a valid archive replaces the current one.
// A network with a state of its own (onnd's recurrent state) drops it in resetHistory().
#pragma once

#include "base/exception.h"
#include "filter/registry.h"
#include "nn/baseline_filter.h" // nn::EmbeddedWeights, nn::baselineFilterType
#include "nn/baseline_input.h"
#include "nn/weights.h"
#include "stages/demodulate.h"

#include <string>
#include <utility>

namespace afn {

/// Names of one such method: the method's name ("mrkp") and its model's ("MR-KP").
struct TaNetworkNames {
    const char* method;
    const char* model;
};

/// The FilterType of a TA-network method: the learned baselines' (nn::baselineFilterType: stages,
/// inputs, feature outputs, quality help) with the 1-spp irradiance as a first feature output.
/// The caller sets create.
inline FilterType taNetworkFilterType(const char* name, const char* description, bool ready)
{
    FilterType t = nn::baselineFilterType(name, description, ready);
    t.features.insert(t.features.begin(),
        { "irradiance", 3, "1-spp colour divided by max(albedo, 2^-10), linear HDR, >= 0" });
    return t;
}

/// Network: load(const nn::WeightsArchive&), loaded(), and
/// run({ &accumulated, &albedo, &normal01, &depth01 }, Image& out).
template <class Network> class TaNetworkFilter : public Filter {
public:
    TaNetworkFilter(const FilterType& t, TaNetworkNames names, nn::EmbeddedWeights embedded)
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
        m_features.compute(in);
        writeFeature("irradiance", irradiance());
        writeFeature("accumulated", accumulator().color());
        writeFeature("albedo", m_features.albedo);
        writeFeature("normal01", m_features.normal01);
        writeFeature("depth01", m_features.depth01);
        if (!outputBound())
            return; // only the network's inputs were asked for
        m_net.run({ &accumulator().color(), &m_features.albedo, &m_features.normal01,
                      &m_features.depth01 },
            m_result);
        reportProgress(0.95);
        remodulate(in, m_result, out);
    }

    TaNetworkNames m_names;
    nn::BaselineFeatures m_features;
    Image m_result;
};

} // namespace afn
