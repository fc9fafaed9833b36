// SPDX-License-Identifier: Apache-2.0
// The Filter of the learned baselines (methods/wskpn, methods/nbgd): both denoise a frame the same
// way and differ only in their network. Per frame, after the shared stages (aux prefilter,
// demodulation, BMFR temporal accumulation: the same TA-1spp colour afn reads): the 10-channel
// input (nn/baseline_input.h), the network on it and on the accumulation, then remodulation by the
// albedo. Weights: an archive embedded at build time or afnSetFilterData(filter, "weights", ...);
// only valid weights replace the current ones. Statistic "stats.<name>.gflop": the last frame's
// network work. baselineFilterType() gives the FilterType fields the baselines share.
#pragma once

#include "base/exception.h"
#include "filter/filter.h"
#include "filter/registry.h"
#include "nn/baseline_input.h"
#include "nn/weights.h"
#include "stages/demodulate.h"

#include <cstddef>
#include <string>
#include <utility>

namespace afn::nn {

/// An archive built into the library; data == nullptr when the build embeds none.
struct EmbeddedWeights {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};

/// A baseline's filter type: name, description, whether it runs as created (embedded weights),
/// the shared stages, inputs, feature outputs and quality help. The caller sets `create`.
FilterType baselineFilterType(const char* name, const char* description, bool ready);

/// Network: load(const WeightsArchive&), loaded(), run(input, cta, out), flopPerPixel().
template <typename Network> class BaselineFilter : public Filter {
public:
    /// `label` names the model in messages ("WSKPN").
    BaselineFilter(const FilterType& t, const std::string& label, EmbeddedWeights embedded)
        : Filter(t)
        , m_name(t.name)
        , m_label(label)
    {
        if (embedded.data)
            m_net.load(WeightsArchive::parse(
                embedded.data, embedded.size, "embedded " + m_label + " weights"));
    }

    void setData(const std::string& name, const void* data, std::size_t size) override
    {
        if (name != AFN_DATA_WEIGHTS)
            Filter::setData(name, data, size);
        Network net;
        net.load(WeightsArchive::parse(data, size, "weights set with afnSetFilterData"));
        m_net = std::move(net); // only valid weights replace the current ones
        markDirty();
        reset();
    }

    bool statistic(const std::string& name, double& value) const override
    {
        if (name != "stats." + m_name + ".gflop")
            return false;
        value = m_net.flopPerPixel() * m_pixels * 1e-9;
        return true;
    }

private:
    void configure() override
    {
        if (outputBound() && !m_net.loaded())
            throwInvalidOperation(m_name + ": no weights: this build embeds no trained " + m_label
                + " model; set an .afnw file with afnSetFilterData(filter, \"weights\", data, "
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
        baselineInput(accumulator().color(), m_features, m_input);
        m_net.run(m_input, accumulator().color(), m_result);
        reportProgress(0.95);
        remodulate(in, m_result, out);
    }

    const std::string m_name, m_label;
    Network m_net;
    BaselineFeatures m_features;
    Image m_input, m_result;
    double m_pixels = 0;
};

} // namespace afn::nn
