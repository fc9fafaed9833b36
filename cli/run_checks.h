// SPDX-License-Identifier: Apache-2.0
// Checks of a whole run, made before any frame is read or written, so that a refused run leaves
// every file as it was: outputs never name a file the run reads, output formats can store what
// -d and --compression ask for, and temporal methods see their frames in time order.
#pragma once

#include "frame_loader.h"

#include <string>
#include <vector>

namespace afntool {

/// A file the run reads, with what it is ("input", "--compare reference", ...), for messages.
struct ReadFile {
    std::string path;
    std::string what;
};

/// Every file the run reads: the input frames (every file of a dataset folder), the --compare
/// references of each frame, the --weights and :weights= files, the colour config.
std::vector<ReadFile> filesRead(const Options& opts, const std::vector<FrameRef>& frames);

/// Refuse (CliError, nothing written) when the output of any action for any frame is one of
/// `reads` (same file by device and inode, so also through symlinks and hard links, or the same
/// canonical path for files not there yet), and when an -o output's format cannot store -d's
/// type or --compression (the message lists the valid choices).
void checkOutputs(
    const Options& opts, const std::vector<FrameRef>& frames, const std::vector<ReadFile>& reads);

/// Refuse frames that are not in strictly ascending order for a --denoise or --features method
/// that carries a temporal history (its parameters include the reprojection's): the history is
/// reprojected with motion vectors that point from each frame to the previous one in time, so a
/// run backwards in time would warp it the wrong way.
void checkFrameOrder(const Options& opts, const std::vector<FrameRef>& frames);

} // namespace afntool
