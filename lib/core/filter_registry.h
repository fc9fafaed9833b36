// SPDX-License-Identifier: Apache-2.0
// The table of filter types. Each method contributes one FilterType (name, description, its own
// parameters, factory); the registry appends the common input-convention parameters.
#pragma once

#include "filter.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace afn {

struct FilterType {
    std::string name;
    std::string description;
    std::vector<ParamDesc> params; ///< full table: method parameters, then the common ones
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

// Per-method descriptions (defined next to each method): method parameters and factory only.
FilterType identityFilterType();
FilterType taFilterType();
FilterType svgfFilterType();
FilterType bmfrFilterType();
FilterType afnFilterType();

/// True when this build embeds trained AFN weights (weights/afn.afnw at configure time), so the
/// "afn" filter runs without weights being set.
bool afnHasEmbeddedWeights();

} // namespace afn
