// SPDX-License-Identifier: Apache-2.0
// How the plugin presents the library's parameters in a host: readable choice labels over stable
// ids, slider display ranges narrower than the accepted ranges, and which parameters only matter
// with auxiliary inputs (hidden in the Filter context, which has none).
#pragma once

#include <afn/afn.h>

#include <string>

namespace afnofx {

/// Label of a method choice option: "ID (what it is)", e.g. "SVGF (spatiotemporal
/// variance-guided filtering)". The first word, lower-cased, is always the library's id: saved
/// projects store the option index (OFX 1.4), the golden test pins the ids through that word.
std::string methodLabel(const std::string& id);

/// Label of a device choice option ("CPU", "CUDA (...)", "Auto (...)"); same first-word rule.
std::string deviceLabel(const std::string& id);

/// Slider range shown for a numeric parameter (kOfxParamPropDisplayMin/Max), inside the accepted
/// range [minValue, maxValue].
struct DisplayRange {
    double min;
    double max;
};
DisplayRange displayRange(const AFNParamInfo& info);

/// True for a library parameter that has no effect without auxiliary inputs (albedo, normal,
/// depth, position, motion): the input conventions every method shares, the history acceptance
/// limits, the aux prefilter and SVGF's normal and depth edge-stopping.
bool needsAuxInputs(const char* name, bool sharedByAllMethods);

} // namespace afnofx
