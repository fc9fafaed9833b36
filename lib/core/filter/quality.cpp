// SPDX-License-Identifier: Apache-2.0
#include "filter/quality.h"

namespace afn {

const ParamBinding<QualitySettings>& qualityBinding()
{
    using T = QualitySettings::Tier;
    static const ParamBinding<QualitySettings> binding
        = ParamBinding<QualitySettings>().add(&QualitySettings::quality, AFN_PARAM_QUALITY,
            { { "fast", T::Fast }, { "balanced", T::Balanced }, { "high", T::High } }, "Quality",
            "cost/accuracy tier");
    return binding;
}

ParamDesc qualityDescriptor(const std::string& help)
{
    ParamDesc d = qualityBinding().descriptors().front();
    d.help = help;
    return d;
}

} // namespace afn
