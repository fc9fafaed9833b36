// SPDX-License-Identifier: Apache-2.0
// --info's "afn:" line: the trained model the afn method chooses for a file's inputs.
#pragma once

#include "options.h"

#include "afn/io.hpp"

#include <string>

namespace afntool {

/// The afn filter's path for `frame`'s roles, as the library reports it at commit
/// (AFN_STAT_AFN_MODEL), e.g. "model color, single-frame (...)"; with --weights, for those
/// weights. When no model fits, "error: " and the library's message.
std::string afnModelFor(const Options& opts, const afn::io::FrameImages& frame);

} // namespace afntool
