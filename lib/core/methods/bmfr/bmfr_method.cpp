// SPDX-License-Identifier: Apache-2.0
// "bmfr": blockwise multi-order feature regression (methods/bmfr/denoiser.h) on the shared
// stages' temporal accumulation of albedo-demodulated colour.
#include "filter/quality.h"
#include "filter/registry.h"
#include "methods/bmfr/denoiser.h"
#include "stages/aux_prefilter.h"

namespace afn::bmfr {

namespace {

class BmfrFilter final : public Filter {
public:
    explicit BmfrFilter(const FilterType& t)
        : Filter(t)
    {
    }

private:
    void configure() override
    {
        Settings s = settingsBinding().read(params());
        s.spp = auxBinding().read(params()).spp; // the shared "spp" parameter
        m_bmfr.setSettings(s);
    }
    void resetHistory() override { m_bmfr.reset(); }
    std::int64_t lastHighlightPixels() const override { return m_bmfr.highlightPixels(); }
    void denoise(const Frame& in, Image& out) override
    {
        out = m_bmfr.process(
            in, reprojector(), accumulator(), accumulatorScratch(), irradianceForReuse());
    }
    // The base writes the denoiser's own output image (the TAA history, or the accumulation's
    // scratch without TAA) into the bound output.
    const Image* denoiseRadiance(const Frame& in) override
    {
        return &m_bmfr.process(
            in, reprojector(), accumulator(), accumulatorScratch(), irradianceForReuse());
    }

    Denoiser m_bmfr;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "bmfr";
    t.description = "blockwise multi-order feature regression (Koskela et al. 2019) with BMFR's "
                    "accumulations and TAA";
    t.params = settingsBinding().descriptors();
    // Quality tiers (filter/quality.h): the regression's cost is fixed per block and its feature
    // set is the method; the one optional pass, TAA (taa=0), saves about 10 % at the same error on
    // examples/sequence (docs/report). No real trade, so bmfr has one level.
    t.qualityHelp = std::string(kQualityOneLevel)
        + " (the block regression is the method; taa=0 saves about 10 % at equal error)";
    t.stages = { true, StageNeeds::Reproject::Bilinear, true };
    t.inputs = { { { AFN_IMAGE_NORMAL }, "regression features" },
        { { AFN_IMAGE_POSITION, AFN_IMAGE_DEPTH }, "regression features" } };
    t.create = factoryOf<BmfrFilter>();
    t.skipHelp = "only the blocks holding a needed pixel (+3 px) are fitted; skipped pixels take "
                 "the accumulated colour through the second accumulation and TAA; needed pixels "
                 "bit-identical to skip=off";
    return t;
}

} // namespace afn::bmfr
