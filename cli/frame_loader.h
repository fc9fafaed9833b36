// SPDX-License-Identifier: Apache-2.0
// Resolving the run's frames (single files, patterns, BMFR dataset folders) and loading each one
// with its roles converted into the working colour space.
#pragma once

#include "options.h"

#include "afn/color.hpp"
#include "afn/io.hpp"

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace afntool {

/// One input frame to process: its path (or BMFR pseudo path) and frame number (-1 for a single
/// file; frame numbers may be negative, so `numbered` says whether there is one).
struct FrameRef {
    std::string path;
    int frame = -1;
    bool numbered = false; ///< from a frame pattern or a dataset folder (--frames)
};

/// The frames named by the inputs and --frames; throws CliError (missing frame named).
std::vector<FrameRef> resolveFrames(const Options& opts);

/// Output path for a frame: patterns expanded; several frames need a pattern.
std::string outputPath(const std::string& pattern, const FrameRef& ref, std::size_t frameCount,
    const std::string& flag);

struct LoadedFrame {
    FrameRef ref;
    afn::io::FrameImages images;
    std::string colorSpace; ///< colour space the beauty was read in (converted to working)
    std::string beautyType; ///< stored type of the beauty: uint8 | uint16 | half | float
    std::vector<float> beauty; ///< current beauty, RGB, working space (replaced by --denoise)
    /// What was done to the beauty so far, one afntool argument per step (--denoise:method=...
    /// with every parameter), for the outputs' history attribute.
    std::vector<std::string> history;
    /// Light passes in images.passes that a --denoise:passes= replaced by denoised ones (working
    /// space, as the beauty); the others there hold the file's values converted to working space.
    std::set<std::string> denoisedPasses;
};

/// Shared state of a run: options and the lazily loaded colour config.
class RunContext {
public:
    explicit RunContext(const Options& opts)
        : m_opts(opts)
    {
    }
    const Options& options() const { return m_opts; }
    afn::color::ColorManager& color();

private:
    const Options& m_opts;
    std::unique_ptr<afn::color::ColorManager> m_color;
};

/// Load a frame for processing (colour required); keepAll reads every channel too.
LoadedFrame loadFrame(RunContext& ctx, const FrameRef& ref, bool keepAll);

} // namespace afntool
