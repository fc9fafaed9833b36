// SPDX-License-Identifier: Apache-2.0
// Writing stress frames as EXR sequences afntool reads (generic layer names: R,G,B,A, albedo.*,
// N.*, Z, P.*, motion.*), and reading afntool's outputs back, through afn_io's public API.
#pragma once

#include "stress_util.h"

#include <string>
#include <vector>

namespace stress {

/// Write `frame` as one float EXR with every role it holds.
void writeExr(const std::string& path, const FrameData& frame);

/// Write frames 0..n-1 at `pattern` (a printf-style "%04d" pattern) and return their paths.
std::vector<std::string> writeExrSequence(
    const std::string& pattern, const std::vector<FrameData>& frames);

/// The colour (R,G,B) of an EXR afntool wrote, as floats.
std::vector<float> readColor(const std::string& path);

/// Bytes of a file, as a string.
std::string fileBytes(const std::string& path);

} // namespace stress
