// SPDX-License-Identifier: Apache-2.0
// Quality tiers: the "quality" parameter (AFN_PARAM_QUALITY) of every denoising method, as Open
// Image Denoise's OIDN_QUALITY_FAST/BALANCED/HIGH. balanced (the default) is the method as it is
// without the parameter, bit-identical; fast trades accuracy for time, high time for accuracy.
// What a tier does is the method's choice, stated in its FilterType::qualityHelp (the parameter's
// help text, so `afntool --help METHOD`, the C API and the plugin show it). A method without a
// real trade accepts all three and runs one filter (kQualityOneLevel says so in its help).
#pragma once

#include "base/params.h"

#include <string>

namespace afn {

struct QualitySettings {
    enum class Tier { Fast, Balanced, High };
    Tier quality = Tier::Balanced; ///< fast | balanced (default) | high
};

/// The binding that reads "quality" back at commit (help text: qualityDescriptor's).
const ParamBinding<QualitySettings>& qualityBinding();

/// The "quality" descriptor of a method whose tiers `help` describes.
ParamDesc qualityDescriptor(const std::string& help);

/// Opening of the help text of a method with one level (its reason follows).
constexpr const char* kQualityOneLevel = "one level: fast, balanced and high run the same filter";

} // namespace afn
