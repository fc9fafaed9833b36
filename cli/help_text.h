// SPDX-License-Identifier: Apache-2.0
// afntool's help: a one-screen overview, per-method detail generated from the methods' parameter
// descriptors (the same table the C API and the plugin read), and the --methods listing.
#pragma once

#include <string>
#include <vector>

namespace afntool {

/// `afntool --help`: usage, actions, settings, methods, in about 40 lines.
std::string helpText();
/// `afntool` with no arguments: the usage lines and where to read more.
std::string usageText();
/// `afntool --help TOPIC`: a method's description, inputs and parameters (name=default, type and
/// range, help) and the input conventions. Throws CliError for an unknown topic (with a
/// suggestion).
std::string topicHelpText(const std::string& topic);
/// Topics `--help TOPIC` knows: the method names.
std::vector<std::string> helpTopics();
/// The --methods listing: "NAME ready|needs-weights DESCRIPTION" per line.
std::string methodsText();

} // namespace afntool
