// SPDX-License-Identifier: Apache-2.0
// Strict argument checks shared by afntool's actions: modifiers each action accepts, --aov
// arguments, method and parameter names; every rejection names what is valid and suggests the
// nearest valid name.
#pragma once

#include "options.h"

#include <string>
#include <vector>

namespace afntool {

/// Parse one --aov argument into `overrides`; CliError for an unknown role (with a suggestion
/// and the valid roles), a malformed channel list or an unknown convention.
void parseAovArgument(const std::string& text, afn::io::MappingOverrides& overrides);

/// Reject modifiers an action does not take (--preview:vew=...), as --denoise rejects unknown
/// parameters; --denoise, --features and --benchmark check their own.
void checkActionModifiers(const Options& opts);

/// CliError unless `method` is a known method (suggestion and the list of methods otherwise).
void checkMethodName(const std::string& flag, const std::string& method);

/// CliError for a modifier of `flag` that is none of the method's parameters nor `extra`
/// ("--denoise: svgf has no parameter 'sigmal' (did you mean 'sigmaL'?)").
void checkMethodParameters(const std::string& flag, const std::string& method,
    const std::map<std::string, std::string>& params, const std::vector<std::string>& extra);

} // namespace afntool
