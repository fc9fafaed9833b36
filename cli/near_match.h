// SPDX-License-Identifier: Apache-2.0
// "Did you mean" suggestions for misspelt options, modifiers, method, parameter and role names.
#pragma once

#include <string>
#include <vector>

namespace afntool {

/// The candidate closest to `given`, or "" when none is close: a case-only difference
/// ("sigmal" -> "sigmaL"), a small edit distance (one edit for names up to 4 characters, two for
/// longer ones; a swap of neighbours counts as one), or a candidate that `given` begins
/// ("--contact" -> "--contact-sheet", at least 4 characters). Ties go to the earlier candidate.
std::string nearMatch(const std::string& given, const std::vector<std::string>& candidates);

/// " (did you mean 'X'?)" for nearMatch(), else "".
std::string didYouMean(const std::string& given, const std::vector<std::string>& candidates);

/// The names joined with ", " (for "known: a, b, c" lists).
std::string joinNames(const std::vector<std::string>& names);

} // namespace afntool
