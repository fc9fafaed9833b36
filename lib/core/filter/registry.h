// SPDX-License-Identifier: Apache-2.0
// The table of filter types: the one place that names the methods. Each method contributes one
// FilterType (methods/<name>/): its name, description, own parameters, the shared stages it
// composes and a factory. The registry completes the parameter table from the stages and the input
// conventions, and creates filters on a device.
#pragma once

#include "base/device.h"
#include "filter/filter.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace afn {

struct FilterType;
/// Creates a filter of a type on a device (the type outlives the filter).
using FilterFactory = std::function<std::unique_ptr<Filter>(const FilterType&, const Device&)>;

struct FilterType {
    std::string name;
    std::string description;
    /// The method's own parameters; after registration the full table: accumulation (when the
    /// stages accumulate), the method's own, quality (when qualityHelp is set), reprojection
    /// (when they reproject), aux (when they demodulate: stages/aux_prefilter.h), work skipping
    /// (filter/work_mask.h), conventions.
    std::vector<ParamDesc> params;
    /// What quality=fast|balanced|high do for this method (the help of its "quality" parameter,
    /// filter/quality.h: appended after its own parameters); empty = no such parameter.
    std::string qualityHelp;
    /// What skip=on does in this method (appended to the help of "skip", filter/work_mask.h):
    /// its cheap path and what stays exact, or that it skips nothing. Empty: "not implemented".
    std::string skipHelp;
    StageNeeds stages;
    std::vector<FeatureOutput> features; ///< feature outputs the method can write
    /// Inputs it reads besides the colour: the method's own; the registry adds those of the
    /// stages (albedo for demodulation, motion or position + camera for reprojection).
    std::vector<InputUse> inputs;
    bool ready = true; ///< runs as created: needs no data, or the build embeds its weights
    std::vector<AFNDeviceType> devices { AFN_DEVICE_TYPE_CPU }; ///< devices it runs on
    FilterFactory create;
};

/// A factory for a method class F constructed as F(const FilterType&).
template <typename F> FilterFactory factoryOf()
{
    return [](const FilterType& t, const Device&) { return std::make_unique<F>(t); };
}

/// Every filter type of this build, in a stable order.
const std::vector<FilterType>& filterTypes();

/// The type with that name, or nullptr.
const FilterType* findFilterType(const std::string& name);

/// Create a filter on a device; throws InvalidArgument naming the known types if the name is
/// unknown, Unsupported if the method does not run on the device.
std::unique_ptr<Filter> createFilter(const std::string& name, const Device& device);
/// Create a filter for the CPU (tests and benchmarks of the core).
std::unique_ptr<Filter> createFilter(const std::string& name);

// Per-method descriptions (defined in methods/<name>/).
namespace identity {
FilterType filterType();
}
namespace ta {
FilterType filterType();
}
namespace svgf {
FilterType filterType();
}
namespace bmfr {
FilterType filterType();
}
namespace afnet {
FilterType filterType();
}
namespace wskpn {
FilterType filterType();
}
namespace nbgd {
FilterType filterType();
}
namespace onnd {
FilterType filterType();
}
namespace mrkp {
FilterType filterType();
}

} // namespace afn
