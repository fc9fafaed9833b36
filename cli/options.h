// SPDX-License-Identifier: Apache-2.0
// afntool's command line: oiiotool-style ordered arguments with ":key=value" modifiers.
// Settings (--frames, --aov, --colorconfig, ...) apply to the whole run; actions (--info,
// --denoise, --preview, --contact-sheet, -o) run per frame in the order given.
#pragma once

#include "afn/io.hpp"

#include <map>
#include <string>
#include <vector>

namespace afntool {

/// One action with its modifiers, e.g. "--denoise:method=svgf:iterations=4".
struct Action {
    std::string name; ///< info | denoise | preview | contact-sheet | output
    std::string arg; ///< output path (preview, contact-sheet, output)
    std::map<std::string, std::string> mods; ///< modifiers in the order given (keys unique)
};

struct Options {
    std::vector<std::string> inputs; ///< files or frame patterns
    std::string frames; ///< "--frames" range text ("" = single files)
    std::string colorConfig; ///< --colorconfig
    std::string inColorSpace; ///< --incolorspace ("" = from the file, else working space)
    std::string outColorSpace; ///< --outcolorspace ("" = the input's colour space)
    afn::io::MappingOverrides overrides;
    int threads = 0; ///< --threads (0 = all cores)
    int preroll = 0; ///< --preroll N: frames before the first one run to rebuild history (farm.md)
    std::string device = "cpu"; ///< --device cpu|cuda|auto: where --denoise runs
    std::string weights; ///< --weights FILE: network weights for afn (and :weights=)
    std::string dataType; ///< -d half|float ("" = keep the input's)
    std::string compression; ///< --compression ("" = keep the input's)
    bool keepAovs = false; ///< --keep-aovs
    bool json = false; ///< --json (with --info)
    std::string report; ///< --report DIR (with --benchmark): report folder
    bool quiet = false; ///< --quiet: no progress, no warnings
    bool verbose = false; ///< -v: every frame's --denoise detail (default: facts once, changes)
    bool help = false;
    std::string helpTopic; ///< --help METHOD
    bool usage = false; ///< no arguments: print the usage lines
    bool methods = false; ///< --methods: one line per method with its readiness
    bool version = false;
    std::vector<Action> actions;
};

/// Parse argv; throws CliError with a message naming the bad argument.
Options parseCommandLine(int argc, const char* const* argv);

/// Split "--name:key=value:key2=value2" into the name and its modifiers.
std::string splitModifiers(const std::string& arg, std::map<std::string, std::string>& mods);

} // namespace afntool
