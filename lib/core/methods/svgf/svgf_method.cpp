// SPDX-License-Identifier: Apache-2.0
// "svgf": spatiotemporal variance-guided filtering (methods/svgf/denoiser.h) on albedo-demodulated
// colour, reprojected by the shared stage with SVGF's box fallback, remodulated, then temporally
// anti-aliased (stages/taa.h; the paper's last step, parameter taa, off by default).
#include "filter/quality.h"
#include "filter/registry.h"
#include "methods/svgf/denoiser.h"
#include "stages/aux_prefilter.h"
#include "stages/demodulate.h"
#include "stages/taa.h"

namespace afn::svgf {

namespace {

class SvgfFilter final : public Filter {
public:
    explicit SvgfFilter(const FilterType& t)
        : Filter(t)
    {
    }

private:
    void configure() override
    {
        m_settings = settingsBinding().read(params());
        m_settings.spp = auxBinding().read(params()).spp; // the shared "spp" parameter
        m_svgf.setSettings(m_settings);
        m_svgf.setTrustSettings(historyTrustBinding().read(params()));
    }
    const HistoryTrust* historyTrust() const override { return &m_svgf.trust(); }
    void resetHistory() override
    {
        m_svgf.reset();
        m_taa.reset();
    }
    std::int64_t lastHighlightPixels() const override { return m_svgf.highlightPixels(); }
    void denoise(const Frame& in, Image& out) override
    {
        remodulate(in, *filter(in), out);
        if (m_settings.taa) {
            const Image& aa
                = m_taa.apply(reprojector(), out, m_settings.taaAlpha, m_taaSpare, &m_svgf.trust());
            out = aa;
        }
    }
    // Without TAA the base remodulates straight into the bound output. The result takes the
    // irradiance's place (read only by the temporal integration, before it is written).
    const Image* denoiseDemodulated(const Frame& in) override
    {
        return m_settings.taa ? nullptr : filter(in);
    }
    // With TAA: remodulated in place, then the TAA's output (its next history) is the result.
    const Image* denoiseRadiance(const Frame& in) override
    {
        Image& radiance = *filter(in);
        remodulate(in, radiance, radiance);
        return &m_taa.apply(
            reprojector(), radiance, m_settings.taaAlpha, m_taaSpare, &m_svgf.trust());
    }
    Image* filter(const Frame& in)
    {
        Image& filtered = irradianceForReuse();
        m_svgf.process(in, irradiance(), reprojector(), filtered);
        return &filtered;
    }

    Settings m_settings;
    TemporalAntialiasing m_taa;
    Image m_taaSpare; ///< the TAA's output buffer (stages/taa.h TemporalAntialiasing::apply)
    Denoiser m_svgf;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "svgf";
    t.description
        = "spatiotemporal variance-guided filtering (Schied et al. 2017), paper parameters";
    t.params = settingsBinding().descriptors();
    // Quality tiers (filter/quality.h): the obvious knob, the number of a-trous iterations, is no
    // monotone trade. On examples/sequence (docs/report) PSNR peaks at 2 iterations (26.2 dB
    // against 25.8 at the paper's 5) while SSIM and the temporal error are best at 4-5, and 1-2
    // iterations save only 16-26 % of the time (the temporal and variance passes stay). So svgf
    // has one level; `iterations` remains the explicit setting.
    t.qualityHelp = std::string(kQualityOneLevel)
        + " (fewer a-trous iterations are not less accurate on every metric: set iterations)";
    t.stages = { true, StageNeeds::Reproject::BilinearWithBoxFallback, false };
    t.inputs = { { { AFN_IMAGE_NORMAL }, "edge-stopping" },
        { { AFN_IMAGE_DEPTH, AFN_IMAGE_POSITION }, "edge-stopping", true } };
    t.create = factoryOf<SvgfFilter>();
    t.skipHelp
        = "(taa=0, the default) the variance estimate and the a-trous passes run only over the "
          "needed pixels dilated by what later passes read; skipped pixels take the "
          "temporally integrated colour; needed pixels bit-identical to skip=off where the "
          "region ends at a depth edge and antilag=0 (the history trust's blocks see the "
          "skipped pixels' history within 32 px). With taa=1 every pixel is filtered "
          "(docs/work-skipping.md)";
    return t;
}

} // namespace afn::svgf
