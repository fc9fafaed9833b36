// SPDX-License-Identifier: Apache-2.0
// "afn": the Adaptive Fusion Network denoiser (Lee et al.). Per frame, after the shared stages
// (aux prefilter, demodulation of the 1-spp colour, BMFR temporal accumulation for TA-1spp; the
// albedo, normal and depth seen here are the prefiltered ones): scale normal and
// depth (stages/feature_scaling.h), run the network (network.h) and remodulate. The network output
// is clamped to >= 0 by the remodulation (stages/demodulate.h). Weights: weights_source.h.
//
// Input-aware: the library holds one trained model per input set (model_set.h,
// input_set.h); each frame runs the model for its inputs, whose absent roles are held neutral and
// which without a temporal history runs single-frame (network_inputs.h). The choice is
// reported as AFN_STAT_AFN_MODEL; no fitting model is an error at commit and at execute.
//
// `spp`, the input's samples per pixel (the parameter shared with the aux prefilter,
// stages/aux_prefilter.h; afntool: from the file's cycles.<layer>.samples unless given), chooses
// among the models for the frame's input set the one trained nearest that count (model_set.h);
// read at commit.
//
// Quality tiers (quality=fast|balanced|high): methods/afn/quality_tiers.h (fast: no refinement;
// balanced: the network as trained; high: a four-flip self-ensemble of the network).
//
// taa=auto|off|on (settings.h; auto: on for the models trained below 16 spp) anti-aliases the
// remodulated output over time (stages/taa.h, shared with svgf and bmfr); every pixel is then
// denoised. Its history is reset whenever a frame runs without it. With work skipping and TAA the
// network computes the rows of the work mask grown by kTaaWorkMargin (as bmfr does,
// bmfr/denoiser.h) and TAA runs on every pixel (skipped ones hold the accumulated colour), so a
// needed pixel is bit-identical to skip=off while it moves less than a pixel per frame relative to
// the mask.
//
// postFilter=auto|off|on (settings.h; auto: on for the models trained below 16 spp) smooths the
// final output (after the TAA, whose history stays the unfiltered output) with an edge-aware
// a-trous filter guided by the frame's albedo, normal and depth (post_filter.h), as strong at each
// pixel as the noise left there (the 1-spp irradiance's local variance over the accumulation's
// history length, post_filter_noise.h). With work skipping the network's rows are grown by
// kPostFilterRadius more.
//
// precision=auto|fp32|bf16 (settings.h; auto: bf16 where the CPU has AVX512_BF16, on AMX tiles
// where it has AMX-BF16 too) sets the arithmetic of the network's convolutions for each frame
// (Network::setPrecision); reported as AFN_STAT_AFN_PRECISION.
//
// On a CUDA device (builds with AFN_HAS_CUDA) the whole filter, shared stages included, runs on
// the GPU instead (cuda/afn_cuda_filter.h); what it does not run yet is listed in docs/gpu.md.
#include "base/exception.h"
#include "cpu/isa.h"
#include "filter/registry.h"
#include "methods/afn/model_set.h"
#include "methods/afn/network.h"
#include "methods/afn/network_inputs.h"
#include "methods/afn/post_filter.h"
#include "methods/afn/quality_tiers.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"
#include "methods/afn/work_rows.h"
#include "stages/aux_prefilter.h"
#include "stages/demodulate.h"
#include "stages/taa.h"

#ifdef AFN_HAS_CUDA
#include "cuda/afn_cuda_filter.h"
#endif

#include <algorithm>
#include <utility>
#include <vector>

namespace afn::afnet {

namespace {

class AfnFilter final : public Filter {
public:
    explicit AfnFilter(const FilterType& t)
        : Filter(t)
        , m_models(ModelSet::embedded())
    {
    }

    void setData(const std::string& name, const void* data, std::size_t size) override
    {
        if (name != AFN_DATA_WEIGHTS)
            Filter::setData(name, data, size);
        m_models = ModelSet::fromData(data, size); // only valid weights replace the current ones
        m_model = nullptr;
        markDirty();
        reset();
    }

    bool stringStatistic(const std::string& name, std::string& value) const override
    {
        if (name != AFN_STAT_AFN_MODEL)
            return false;
        value = m_path;
        return true;
    }

    std::int64_t lastHighlightPixels() const override { return m_highlights.pixels(); }

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
        if (rest == "precision") {
            value = runsBf16() ? 16.0 : 32.0;
            return true;
        }
        if (rest == "bf16Hardware") {
            value = runsBf16() && cpu::activeBf16Mode() != cpu::Bf16Mode::Emulated ? 1.0 : 0.0;
            return true;
        }
        if (rest == "bf16Amx") {
            value = runsBf16() && cpu::activeBf16Mode() == cpu::Bf16Mode::Amx ? 1.0 : 0.0;
            return true;
        }
        if (rest == "prediction.inputMs") {
            value = m_tiers.totals().inputMs;
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
        m_spp = auxBinding().read(params()).spp; // the shared "spp" parameter
        m_quality = qualityBinding().read(params()).quality;
        m_settings = settingsBinding().read(params());
        (void)precisionToRun(); // precision=bf16 without the AVX-512 engine fails the commit
        if (!outputBound())
            return;
        if (m_models.empty())
            throwNoWeights();
        // The model for the bound inputs: a missing one fails the commit (and is reported by
        // afntool --info); execute chooses again from each frame's own inputs.
        InputSet bound;
        bound.albedo = imageBound(AFN_IMAGE_ALBEDO);
        bound.normal = imageBound(AFN_IMAGE_NORMAL);
        bound.depth = imageBound(AFN_IMAGE_DEPTH);
        bound.temporal
            = imageBound(AFN_IMAGE_MOTION) || (imageBound(AFN_IMAGE_POSITION) && cameraSet());
        m_model = m_models.choose(bound, m_spp);
        if (!m_model)
            m_models.throwNoModelFor(bound);
        m_path = describeChoice(bound, *m_model);
        // The accumulation's minimum blend for this model (settings.h, alphaMinHighSpp).
        AccumulationSettings accumulation = accumulationBinding().read(params());
        accumulation.alphaMin
            = accumulationAlphaMin(m_settings, accumulation.alphaMin, m_model->spp);
        setAccumulationSettings(accumulation);
    }
    int samplesMadeFor() const override { return m_model ? m_model->spp : 1; }
    void resetHistory() override { m_taa.reset(); }
    void denoise(const Frame& in, Image& out) override
    {
        Image& result = accumulatorScratch();
        if (!run(in, result))
            return;
        m_inputs.radiance(in, result, out);
        if (!m_postOn)
            addHighlights(in, out); // before the TAA, whose output is its next history
        if (m_taaOn)
            out = m_taa.apply(reprojector(), out, m_settings.taaAlpha, m_taaSpare, historyTrust());
        if (m_postOn) {
            edgeAwarePostFilter(out, guidesOf(in), m_postWorkspace, result);
            out = result;
            addHighlights(in, out);
        }
    }
    // The network writes into the accumulation stage's scratch image, its result becomes the
    // radiance in place and the base writes it into the bound output (to save memory: no
    // frame-size result or radiance image of afn's or the base's own). With taa=1 the TAA's output
    // (its next history) is the result.
    const Image* denoiseRadiance(const Frame& in) override
    {
        Image& result = accumulatorScratch();
        run(in, result);
        m_inputs.radiance(in, result, result);
        if (!m_postOn) {
            addHighlights(in, result); // before the TAA, whose output is its next history
            if (m_taaOn)
                return &m_taa.apply(
                    reprojector(), result, m_settings.taaAlpha, m_taaSpare, historyTrust());
            return &result;
        }
        // The post-filter reads the TAA's output (its next history, kept as it is) and writes
        // the result; without TAA it writes the TAA's spare image, then the two swap.
        if (m_taaOn) {
            const Image& aa = m_taa.apply(
                reprojector(), result, m_settings.taaAlpha, m_taaSpare, historyTrust());
            edgeAwarePostFilter(aa, guidesOf(in), m_postWorkspace, result);
        } else {
            edgeAwarePostFilter(result, guidesOf(in), m_postWorkspace, m_taaSpare);
            std::swap(result, m_taaSpare);
        }
        addHighlights(in, result);
        return &result;
    }
    /// Add the highlight bypass's excess (stages/highlight_bypass.h) to the radiance `out`.
    void addHighlights(const Frame& in, Image& out) const
    {
        m_highlights.addExcess(
            out, [&](int x, int y, int k) { return m_inputs.radianceFactor(in, x, y, k); });
    }
    PostFilterGuides guidesOf(const Frame& in) const
    {
        PostFilterGuides g;
        // The noise scale reads the 1-spp irradiance the network reads (the base demodulated
        // the colour in place) and the accumulation's history length.
        g.noise.irradiance = &in.color;
        g.noise.historyLength = &accumulator().historyLength();
        g.noise.maxSamples = accumulator().effectiveSamplesLimit();
        g.albedo = &in.albedo;
        g.normal = &in.normal;
        g.depth = &in.depth;
        return g;
    }
    /// Prepare the inputs (and write the feature outputs) and, when "output" is bound, run the
    /// network into `result`; false when only features were asked for.
    bool run(const Frame& in, Image& result)
    {
        reportProgress(0.1);
        // The model for this frame's inputs (model_set.h); feature-only runs (training data)
        // prepare the inputs of a model for exactly the frame's input set.
        const InputSet available = inputSetOf(in);
        InputSet use = available;
        if (outputBound()) {
            m_model = m_models.choose(available, m_spp);
            if (!m_model)
                m_models.throwNoModelFor(available);
            use = inputsToUse(available, *m_model);
        }
        m_path = outputBound() ? describeChoice(available, *m_model) : describePath(available, use);
        // history01 only where something reads it (4 bytes per pixel otherwise saved).
        const bool history
            = !outputBound() || featureBound("history01") || m_model->net.hasHistoryInput();
        m_inputs.prepare(in, use, irradiance(), accumulator().color(),
            history ? &accumulator().historyLength() : nullptr);
        writeFeature("irradiance", m_inputs.color1());
        writeFeature("accumulated", m_inputs.colorTa());
        writeFeature("albedo", m_inputs.albedo());
        writeFeature("normal01", m_inputs.normal01());
        writeFeature("depth01", m_inputs.depth01());
        if (!m_inputs.history01().empty())
            writeFeature("history01", m_inputs.history01());
        if (!outputBound())
            return false; // only the network's inputs were asked for
        // Every model runs through the same quality tier (quality_tiers.h) and work skipping
        // (network.h: skipped stripes take inputs().colorTa, the model's own TA input).
        // With TAA the rows around the needed ones too (its neighbourhood and next history).
        m_taaOn = taaOn(m_settings, m_model->spp);
        m_postOn = postFilterOn(m_settings, m_model->spp);
        const Image* work = &in.work;
        const int margin = workMargin(m_taaOn, m_postOn);
        if (margin > 0) {
            growWorkRows(in.work, margin, m_workGrown);
            work = &m_workGrown;
        }
        if (!m_taaOn) {
            m_taa.reset(); // a later frame with TAA starts without a stale history
        }
        m_model->net.setPrecision(precisionToRun());
        // Highlights far above the frame's level skip the filters (stages/highlight_bypass.h).
        Inputs inputs = m_inputs.inputs();
        m_highlights.split(*inputs.colorTa, highlightLimit(*inputs.colorTa, m_settings.highlights));
        inputs.color1 = &m_highlights.clamped(*inputs.color1, 0);
        inputs.colorTa = &m_highlights.clamped(*inputs.colorTa, 1);
        m_tiers.run(m_quality, m_model->net, inputs, result, work);
        reportProgress(0.95);
        return true;
    }

    /// Settings::precision for this CPU (settings.h): auto is bf16 only on bf16 instructions
    /// (AVX512_BF16 or AMX); bf16 needs the AVX-512 engine.
    nn::Precision precisionToRun() const
    {
        const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
        switch (m_settings.precision) {
        case Settings::Precision::Fp32:
            return nn::Precision::Fp32;
        case Settings::Precision::Bf16:
            if (!avx512)
                throwInvalidArgument("afn: precision=bf16 needs the AVX-512 engine (this CPU has "
                                     "no AVX-512F, or AFN_CPU_ISA=portable is set); use "
                                     "precision=auto or fp32");
            return nn::Precision::Bf16;
        default:
            return avx512 && cpu::activeBf16Mode() != cpu::Bf16Mode::Emulated ? nn::Precision::Bf16
                                                                              : nn::Precision::Fp32;
        }
    }

    /// What the network runs in (AFN_STAT_AFN_PRECISION): precisionToRun(), fp32 for AFN large.
    bool runsBf16() const
    {
        return precisionToRun() == nn::Precision::Bf16
            && !(m_model && m_model->net.variant() == Variant::Large);
    }

    int m_spp = 0; ///< samples per pixel of the input, 0 = unknown
    QualitySettings::Tier m_quality = QualitySettings::Tier::Balanced;
    Settings m_settings;
    bool m_taaOn = false; ///< this frame's output is anti-aliased (Settings::taa)
    TemporalAntialiasing m_taa;
    Image m_taaSpare; ///< the TAA's output buffer (stages/taa.h TemporalAntialiasing::apply)
    bool m_postOn = false; ///< this frame's output is post-filtered (Settings::postFilter)
    PostFilterWorkspace m_postWorkspace; ///< the post-filter's rows, kept from frame to frame
    Image m_workGrown; ///< the work mask's rows grown by the TAA's and post-filter's margins
    TierRunner m_tiers;
    ModelSet m_models;
    Model* m_model = nullptr; ///< the last frame's (in m_models)
    std::string m_path; ///< describePath() of the last frame
    NetworkInputs m_inputs;
    HighlightBypass m_highlights; ///< this frame's (stages/highlight_bypass.h)
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
    t.qualityHelp = "fast: no refinement network (the fused output; at 1 spp, with the "
                    "post-filter, about 0.8x balanced's time at 1080p and 0.1 dB less PSNR on "
                    "the held-out scenes; 0.65x without it); balanced: the network as trained; "
                    "high: the network on the frame and its three flips, flipped back and "
                    "averaged (at 1 spp about 2.3x balanced's time and 0.03 dB more; 4x without "
                    "the post-filter)";
    t.inputs = { { { AFN_IMAGE_NORMAL }, "network features" },
        { { AFN_IMAGE_DEPTH }, "network features" } };
    t.features = {
        { "irradiance", 3, "1-spp colour divided by max(albedo, 2^-10), linear HDR, >= 0" },
        { "accumulated", 3,
            "BMFR temporal accumulation of the irradiance (TA-1spp), linear HDR; the irradiance "
            "itself without motion or position (single-frame)" },
        { "albedo", 3,
            "demodulation factor = the albedo after the aux prefilter (as given when clean), "
            "[0, 1] (1 without an albedo input); the network input and the remodulation" },
        { "normal01", 3,
            "prefiltered shading normal * 0.5 + 0.5, [0, 1] (0.5 without a normal input)" },
        { "depth01", 1, "prefiltered per-frame min-max depth, [0, 1] (0 without a depth input)" },
        { "history01", 1,
            "1 / the frames the accumulated input holds (history length after the history "
            "trust), [1/255, 1]; 1 without motion or position; the 14th input of models "
            "trained with it" },
    };
#ifdef AFN_HAS_CUDA
    t.devices = { AFN_DEVICE_TYPE_CPU, AFN_DEVICE_TYPE_CUDA };
#endif
    t.create = create;
    t.skipHelp = "the network (CPU) skips the rows without a needed pixel (with TAA: within 3 "
                 "rows of one; with the post-filter: 14 more), in 8-row steps; those pixels take "
                 "the temporally accumulated colour (and TAA, post-filter); needed pixels "
                 "bit-identical to skip=off (with TAA while they move less than a pixel per frame "
                 "relative to the mask); on a CUDA device the same pixels take that colour, "
                 "the network still runs over them";
    return t;
}

} // namespace afn::afnet
