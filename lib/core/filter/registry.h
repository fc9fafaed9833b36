// SPDX-License-Identifier: Apache-2.0
// The table of filter types. Each method contributes one FilterType (name, description, its own
// parameters, factory); the registry appends the common input-convention parameters.
#pragma once

#include "filter/filter.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace afn {

struct FilterType {
    std::string name;
    std::string description;
    std::vector<ParamDesc> params; ///< full table: method parameters, then the common ones
    bool ready = true; ///< runs as created: needs no data, or the build embeds its weights
    std::function<std::unique_ptr<Filter>(const std::vector<ParamDesc>* table)> create;
};

/// Parameters every filter has: conventions of the bound inputs.
std::vector<ParamDesc> commonParams();

/// Every filter type of this build, in a stable order.
const std::vector<FilterType>& filterTypes();

/// The type with that name, or nullptr.
const FilterType* findFilterType(const std::string& name);

/// Create a filter; throws InvalidArgument naming the known types if the name is unknown.
std::unique_ptr<Filter> createFilter(const std::string& name);

// Per-method descriptions (defined in methods/<name>/): method parameters and factory only.
namespace identity { FilterType filterType(); }
namespace ta { FilterType filterType(); }
namespace svgf { FilterType filterType(); }
namespace bmfr { FilterType filterType(); }
namespace afnet { FilterType filterType(); }

/// True when this build embeds trained AFN weights (weights/afn.afnw at configure time), so the
/// "afn" filter runs without weights being set.

} // namespace afn
