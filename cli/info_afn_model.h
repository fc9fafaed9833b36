// SPDX-License-Identifier: Apache-2.0
// --info's "afn:" lines: the trained model the afn method chooses for a file's inputs and the
// network's arithmetic.
#pragma once

#include "options.h"

#include "afn/afn.hpp"
#include "afn/io.hpp"

#include <string>

namespace afntool {

/// The afn filter's path for `frame`'s roles, as the library reports it at commit
/// (AFN_STAT_AFN_MODEL), e.g. "model color, single-frame (...)"; with --weights, for those
/// weights. When no model fits, "error: " and the library's message. `network` (when given)
/// receives the arithmetic the network would run in on this CPU (networkArithmetic), "" on an
/// error.
std::string afnModelFor(
    const Options& opts, const afn::io::FrameImages& frame, std::string* network = nullptr);

/// The arithmetic a committed afn filter's network runs in: "bf16 (AMX)", "bf16 (AVX512_BF16)",
/// "bf16 (emulated)" or "fp32" (AFN_STAT_AFN_PRECISION, _BF16_AMX, _BF16_HARDWARE).
std::string networkArithmetic(const afn::FilterRef& filter);

} // namespace afntool
