// SPDX-License-Identifier: Apache-2.0
// Farm chunks: --preroll N runs the N frames before a chunk's first frame through the run's
// --denoise / --features filters, so their temporal history is rebuilt before the chunk itself is
// processed. Nothing is written, compared or counted for those frames (docs/farm.md).
#pragma once

#include "frame_loader.h"

#include <vector>

namespace afntool {

class Progress;
class SequenceDenoiser;

/// Refuse --preroll where it means nothing: without --denoise/--features, with --benchmark.
void checkPrerollUse(const Options& opts);

/// The preroll frames of `chunk`, oldest first: up to opts.preroll frames before the chunk's
/// first frame, at the chunk's step (the difference of its first two frames, else 1). Walking
/// back, the first missing file is the sequence start and ends the preroll (a clamp, noted on
/// stderr); a missing file with an existing one before it is a hole and an error naming it.
/// Only frame patterns have frames before the chunk; other inputs are refused.
std::vector<FrameRef> resolvePrerollFrames(const Options& opts, const std::vector<FrameRef>& chunk);

/// Run the preroll frames through `denoiser` and `featureWriter` (either may be null) in the
/// order of the actions, advancing their history; other actions do not run for these frames.
/// `progress` counts them as items 0..preroll.size()-1.
void runPreroll(RunContext& ctx, const std::vector<FrameRef>& preroll, SequenceDenoiser* denoiser,
    SequenceDenoiser* featureWriter, Progress& progress);

} // namespace afntool
