// SPDX-License-Identifier: Apache-2.0
// "svgf": spatiotemporal variance-guided filtering (methods/svgf/denoiser.h) on albedo-demodulated
// colour, reprojected by the shared stage with SVGF's box fallback.
#include "filter/quality.h"
#include "filter/registry.h"
#include "methods/svgf/denoiser.h"
#include "stages/demodulate.h"

namespace afn::svgf {

namespace {

class SvgfFilter final : public Filter {
public:
    explicit SvgfFilter(const FilterType& t)
        : Filter(t)
    {
    }

private:
    void configure() override { m_svgf.setSettings(settingsBinding().read(params())); }
    void resetHistory() override { m_svgf.reset(); }
    void denoise(const Frame& in, Image& out) override
    {
        remodulate(in, *denoiseDemodulated(in), out);
    }
    // The base remodulates straight into the bound output. The result takes the irradiance's
    // place (read only by the temporal integration, before it is written).
    const Image* denoiseDemodulated(const Frame& in) override
    {
        Image& filtered = irradianceForReuse();
        m_svgf.process(in, irradiance(), reprojector(), filtered);
        return &filtered;
    }

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
    t.skipHelp = "the variance estimate and the a-trous passes run only over the needed pixels "
                 "dilated by what later passes read; skipped pixels take the temporally "
                 "integrated colour; needed pixels bit-identical to skip=off where the region "
                 "ends at a depth edge (docs/work-skipping.md)";
    return t;
}

} // namespace afn::svgf
