// SPDX-License-Identifier: Apache-2.0
// Which rows afn's network computes under work skipping (filter/work_mask.h): the engines
// (Network::run, the CUDA filter) and the afn method share these rules, so that a skipped row is
// the same everywhere.
#pragma once

#include "base/image.h"

#include <vector>

namespace afn::afnet {

/// `dst` (1 ch, `work`'s size) = 1 on every row within `margin` rows of a row of `work` that holds
/// a pixel > 0, 0 elsewhere (the network computes whole rows, so only rows matter). An empty
/// `work` (no skipping) gives an empty `dst`.
void growWorkRows(const Image& work, int margin, Image& dst);

/// Per row of a frame of height h, 1 where the network computes it: the rows of each 8-row block
/// (of the frame padded to a multiple of 8) that holds a pixel != 0 of `work`; every row without a
/// mask (null or empty). The other rows take the cheap path (Network::run).
std::vector<char> computedRows(const Image* work, int h);

/// The rows around the needed ones afn's output stages read: the TAA's kTaaWorkMargin (its
/// neighbourhood and next history) and the post-filter's kPostFilterRadius, as they are on.
int workMargin(bool taa, bool postFilter);

/// computedRows() of `work` grown by `margin` rows (growWorkRows(); `grown` its scratch); every
/// row without a mask.
std::vector<char> computedRows(const Image& work, int margin, int h, Image& grown);

} // namespace afn::afnet
