// SPDX-License-Identifier: Apache-2.0
// "afn": the Adaptive Fusion Network denoiser (Lee et al.). Per frame, after the shared stages
// (aux prefilter, demodulation of the 1-spp colour, BMFR temporal accumulation for TA-1spp; the
// albedo, normal and depth seen here are the prefiltered ones): scale normal and
// depth (features.h), run the network (network.h) and remodulate. The network output is clamped
// to >= 0 by the remodulation (stages/demodulate.h). Weights: weights_source.h.
//
// Settings (settings.h): `spp`, the input's samples per pixel, which will choose between the
// low- and high-count models; read at commit.
//
// Quality tiers (quality=fast|balanced|high): methods/afn/quality_tiers.h (fast: no refinement;
// balanced: the network as trained; high: a four-flip self-ensemble of the network).
//
// On a CUDA device (builds with AFN_HAS_CUDA) the whole filter, shared stages included, runs on
// the GPU instead (cuda/afn_cuda_filter.h). It has no aux prefilter yet: it refuses aux=noisy and
// runs aux=auto as clean (docs/gpu.md).
#include "base/exception.h"
#include "cpu/isa.h"
#include "filter/registry.h"
#include "methods/afn/features.h"
#include "methods/afn/network.h"
#include "methods/afn/quality_tiers.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"
#include "stages/demodulate.h"

#ifdef AFN_HAS_CUDA
#include "cuda/afn_cuda_filter.h"
#endif

#include <algorithm>

namespace afn::afnet {

namespace {

class AfnFilter final : public Filter {
public:
    explicit AfnFilter(const FilterType& t)
        : Filter(t)
    {
        loadEmbeddedNetwork(m_net);
    }

    void setData(const std::string& name, const void* data, std::size_t size) override
    {
        if (name != AFN_DATA_WEIGHTS)
            Filter::setData(name, data, size);
        m_net = networkFromData(data, size); // only valid weights replace the current ones
        markDirty();
        reset();
    }

    bool statistic(const std::string& name, double& value) const override
    {
        const std::string prefix = "stats.afn.";
        if (name.rfind(prefix, 0) != 0)
            return false;
        const std::string rest = name.substr(prefix.size());
        if (rest == "avx512") {
            value = cpu::activeIsa() == cpu::Isa::Avx512 ? 1.0 : 0.0;
            return true;
        }
        for (int k = 0; k < Network::kStages; ++k) {
            const auto s = static_cast<Network::Stage>(k);
            const std::string stage = Network::stageName(s);
            if (rest == stage + ".ms") // summed over the quality tier's passes
                value = m_tiers.totals().ms[k];
            else if (rest == stage + ".gflop")
                value = m_tiers.totals().flop[k] * 1e-9;
            else
                continue;
            return true;
        }
        return false;
    }

private:
    void configure() override
    {
        m_settings = settingsBinding().read(params());
        m_quality = qualityBinding().read(params()).quality;
        if (outputBound() && !m_net.loaded())
            throwNoWeights();
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
        m_tiers.run(m_quality, m_net, net, m_result, &in.work); // work skipping: network.h
        reportProgress(0.95);
        remodulate(in, m_result, out);
    }

    Settings m_settings;
    QualitySettings::Tier m_quality = QualitySettings::Tier::Balanced;
    TierRunner m_tiers;
    Network m_net;
    Image m_albedo, m_normal01, m_depth01, m_result;
};

std::unique_ptr<Filter> create(const FilterType& t, const Device& device)
{
#ifdef AFN_HAS_CUDA
    if (device.type() == AFN_DEVICE_TYPE_CUDA)
        return cuda::createAfnCudaFilter(t, device);
#else
    (void)device;
#endif
    return std::make_unique<AfnFilter>(t);
}

} // namespace

const ParamBinding<Settings>& settingsBinding()
{
    using S = Settings;
    static const ParamBinding<S> binding
        = ParamBinding<S>().add(&S::spp, "spp", 0, 1 << 20, "Samples per pixel",
            "samples per pixel of the colour input, which chooses the model trained for that count "
            "(0 = unknown: the low-count model); afntool reads it from the file (Blender: "
            "cycles.<layer>.samples) unless given");
    return binding;
}

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
    t.params = settingsBinding().descriptors();
    t.qualityHelp = "fast: no refinement network (the fused output; about 0.85x balanced's "
                    "time at 1080p, 0.5 dB less PSNR on the held-out scenes); balanced: the "
                    "network as trained; high: the network on the frame and its three flips, "
                    "flipped back and averaged (about 3x balanced's time, 0.1-0.3 dB more)";
    t.inputs = { { { AFN_IMAGE_NORMAL }, "network features" },
        { { AFN_IMAGE_DEPTH }, "network features" } };
    t.features = {
        { "irradiance", 3, "1-spp colour divided by max(albedo, 2^-10), linear HDR, >= 0" },
        { "accumulated", 3, "BMFR temporal accumulation of the irradiance (TA-1spp), linear HDR" },
        { "albedo", 3,
            "demodulation factor = the albedo after the aux prefilter (as given when clean), "
            "[0, 1] (1 without an albedo input); the network input and the remodulation" },
        { "normal01", 3,
            "prefiltered shading normal * 0.5 + 0.5, [0, 1] (0.5 without a normal input)" },
        { "depth01", 1, "prefiltered per-frame min-max depth, [0, 1] (0 without a depth input)" },
    };
#ifdef AFN_HAS_CUDA
    t.devices = { AFN_DEVICE_TYPE_CPU, AFN_DEVICE_TYPE_CUDA };
#endif
    t.create = create;
    return t;
}

} // namespace afn::afnet
