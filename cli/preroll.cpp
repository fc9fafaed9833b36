// SPDX-License-Identifier: Apache-2.0
#include "preroll.h"

#include "cli_error.h"
#include "ops.h"
#include "progress.h"

#include <filesystem>

namespace afntool {

namespace {

/// Below any frame number a file name holds: the walk back stops there (and cannot overflow).
constexpr long long kLowestFrame = -9999999;

bool hasAction(const Options& opts, const std::string& name)
{
    for (const Action& a : opts.actions)
        if (a.name == name)
            return true;
    return false;
}

bool frameExists(const std::string& pattern, int frame)
{
    std::error_code ec;
    return std::filesystem::exists(afn::io::expandFramePattern(pattern, frame), ec);
}

} // namespace

void checkPrerollUse(const Options& opts)
{
    if (opts.preroll == 0)
        return;
    // A benchmark times methods over the whole sequence from a cold start: no chunks there.
    if (hasAction(opts, "benchmark"))
        throw CliError("--preroll does not apply to --benchmark (it times whole sequences)");
    if (!hasAction(opts, "denoise") && !hasAction(opts, "features"))
        throw CliError("--preroll needs --denoise or --features (it rebuilds their temporal "
                       "history; nothing else keeps state between frames)");
}

std::vector<FrameRef> resolvePrerollFrames(const Options& opts, const std::vector<FrameRef>& chunk)
{
    if (opts.preroll == 0 || chunk.empty())
        return {};
    if (opts.inputs.size() != 1 || !afn::io::hasFramePattern(opts.inputs[0]) || opts.frames.empty())
        throw CliError("--preroll needs a frame pattern input with --frames (e.g. shot.####.exr "
                       "--frames 40-79)");
    const std::string& pattern = opts.inputs[0];
    const int first = chunk[0].frame;
    // The chunk's own step, so "--frames 40-79x2 --preroll 4" prerolls 32, 34, 36, 38 as a
    // sequential "--frames 0-79x2" would have run them. Unordered lists fall back to 1.
    const int step = chunk.size() > 1 && chunk[1].frame > first ? chunk[1].frame - first : 1;

    std::vector<FrameRef> frames; // newest first while walking back
    for (int k = 1; k <= opts.preroll; ++k) {
        const long long f = static_cast<long long>(first) - static_cast<long long>(k) * step;
        if (f < kLowestFrame)
            break;
        const int frame = static_cast<int>(f);
        if (frameExists(pattern, frame)) {
            frames.push_back({ afn::io::expandFramePattern(pattern, frame), frame });
            continue;
        }
        // The first missing file is the sequence start, unless an older frame exists: a hole.
        if (f - step >= kLowestFrame && frameExists(pattern, frame - step))
            throw CliError("--preroll: frame " + std::to_string(frame) + " is missing but frame "
                    + std::to_string(frame - step)
                    + " exists (a hole in the sequence, not its start)",
                afn::io::expandFramePattern(pattern, frame));
        note("--preroll: " + std::to_string(frames.size()) + " of " + std::to_string(opts.preroll)
                + " frames before frame " + std::to_string(first) + " (frame "
                + std::to_string(frame) + " is missing: the sequence starts after it)",
            opts.quiet);
        break;
    }
    return { frames.rbegin(), frames.rend() };
}

void runPreroll(RunContext& ctx, const std::vector<FrameRef>& preroll, SequenceDenoiser* denoiser,
    SequenceDenoiser* featureWriter, Progress& progress)
{
    const Options& opts = ctx.options();
    for (std::size_t i = 0; i < preroll.size(); ++i) {
        progress.update(static_cast<int>(i), "preroll " + preroll[i].path);
        LoadedFrame frame = loadFrame(ctx, preroll[i], false);
        for (const Action& a : opts.actions) {
            if (a.name == "denoise")
                denoiser->process(frame, &progress);
            else if (a.name == "features")
                featureWriter->advance(frame, &progress);
        }
    }
}

} // namespace afntool
