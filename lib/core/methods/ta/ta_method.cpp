// SPDX-License-Identifier: Apache-2.0
// "ta": BMFR temporal accumulation only (the shared stages). Output = albedo-remodulated
// accumulated irradiance (the TA-1spp input of AFN, WSKPN and NBGD, remodulated).
#include "filter/quality.h"
#include "filter/registry.h"
#include "stages/demodulate.h"

namespace afn::ta {

namespace {

class TaFilter final : public Filter {
public:
    explicit TaFilter(const FilterType& t)
        : Filter(t)
    {
    }

private:
    void denoise(const Frame& in, Image& out) override
    {
        remodulate(in, accumulator().color(), out);
    }
    // The base remodulates straight into the bound output (in the accumulation's pass:
    // outputIsAccumulation).
    const Image* denoiseDemodulated(const Frame&) override { return &accumulator().color(); }
    bool outputIsAccumulation() const override { return true; }
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "ta";
    t.description = "temporal accumulation only, exactly as BMFR (bilinear reprojection, per-tap "
                    "position/normal acceptance, alpha = max(1/(n+1), alphaMin))";
    t.stages = { true, StageNeeds::Reproject::Bilinear, true };
    // Quality tiers (filter/quality.h): one reprojection and one blend per pixel leave nothing to
    // drop, and a longer history is alphaMin's choice, not a cost.
    t.qualityHelp = std::string(kQualityOneLevel)
        + " (one reprojection and blend per pixel: nothing to drop; history length is alphaMin)";
    t.create = factoryOf<TaFilter>();
    t.skipHelp = "nothing to skip: the temporally accumulated colour, which is the cheap path, "
                 "is ta's output on every pixel (the accumulation runs everywhere to keep the "
                 "history complete)";
    return t;
}

} // namespace afn::ta
