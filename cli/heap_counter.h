// SPDX-License-Identifier: Apache-2.0
// afntool's heap counter: the global operator new/delete are replaced (heap_counter.cpp) so that
// --benchmark:size can report the peak heap bytes of each run, the library's allocations included
// (libafn resolves operator new to afntool's). Bytes are malloc_usable_size of each block.
#pragma once

#include <cstddef>

namespace afntool::heap {

/// Bytes allocated through operator new and not yet freed.
std::size_t liveBytes();
/// Highest liveBytes() since the last resetPeak().
std::size_t peakBytes();
/// Start a new peak at the current live bytes.
void resetPeak();

} // namespace afntool::heap
