// SPDX-License-Identifier: Apache-2.0
// The image names of light-path passes ("pass.<name>", "passFactor.<name>", "passOutput.<name>";
// include/afn/afn.h) among a filter's bindings: recognised, checked at commit, gathered for the
// pass transfer (stages/pass_transfer.h).
#pragma once

#include "filter/filter.h"

#include <map>
#include <string>
#include <vector>

namespace afn {

/// True for "pass.<name>", "passFactor.<name>" and "passOutput.<name>" with a non-empty name.
bool isPassImageName(const std::string& name);

/// Throw (naming the image) unless every pass image has 3 channels or more, every factor and
/// output has its pass, every pass its output, and "output" is bound when a pass output is.
void validatePassImages(const std::map<std::string, ImageBinding>& images, bool outputBound);

/// The bound passes with their factors and outputs, in name order.
std::vector<PassBinding> passBindingsOf(const std::map<std::string, ImageBinding>& images);

} // namespace afn
