// SPDX-License-Identifier: Apache-2.0
#include "nn/baseline_filter.h"

#include "filter/quality.h"

namespace afn::nn {

FilterType baselineFilterType(const char* name, const char* description, bool ready)
{
    FilterType t;
    t.name = name;
    t.description = description;
    t.ready = ready;
    t.stages = { true, StageNeeds::Reproject::Bilinear, true };
    t.inputs = { { { AFN_IMAGE_NORMAL }, "network features" },
        { { AFN_IMAGE_DEPTH }, "network features" } };
    t.features = {
        { "accumulated", 3, "BMFR temporal accumulation of the irradiance (TA-1spp), linear HDR" },
        { "albedo", 3, "demodulation factor (the albedo after the aux prefilter), [0, 1]" },
        { "normal01", 3, "prefiltered shading normal * 0.5 + 0.5, [0, 1]" },
        { "depth01", 1, "prefiltered per-frame min-max depth, [0, 1]" },
    };
    // Quality tiers (filter/quality.h): a baseline is reproduced as its paper defines it, one
    // network and one filter; a cheaper or dearer variant would be another model.
    t.qualityHelp = std::string(kQualityOneLevel) + " (a paper baseline: one trained model)";
    return t;
}

} // namespace afn::nn
