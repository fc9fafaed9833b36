// SPDX-License-Identifier: Apache-2.0
// afntool's actions. Each calls the libraries' public APIs; no pixel math lives in the CLI.
#pragma once

#include "frame_loader.h"

#include "afn/afn.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace afntool {

class Progress;

/// --info: print layers, channels, windows, role mapping and per-role statistics (text or JSON).
void runInfo(RunContext& ctx, const std::vector<FrameRef>& frames);

/// -o: write the current beauty as top-level R,G,B[,A] (+ other layers with --keep-aovs).
void writeOutput(RunContext& ctx, const LoadedFrame& frame, const std::string& path,
    const std::vector<std::string>& inputs);

/// --preview: the current beauty through the OCIO display/view (:display= :view=) to an 8-bit
/// image.
void writePreview(RunContext& ctx, const LoadedFrame& frame, const Action& action,
    const std::string& path, const std::vector<std::string>& inputs);

/// --contact-sheet: every role and every other layer of the frame as labelled tiles.
void writeContactSheet(RunContext& ctx, const LoadedFrame& frame, const Action& action,
    const std::string& path, const std::vector<std::string>& inputs);

/// --denoise, or --features: one afn filter kept across the frames of the run (history in frame
/// order).
class SequenceDenoiser {
public:
    /// From a --denoise or a --features action (:method=, default afn for --features).
    SequenceDenoiser(const Options& opts, const Action& action);
    /// --denoise: denoise the frame's beauty in place; warnings go through `progress`.
    void process(LoadedFrame& frame, Progress* progress);
    /// --features: write the method's feature outputs for the frame (the network's inputs as the
    /// method prepares them) to `path`, a float EXR with one layer per feature; the beauty is
    /// left as it is and the network does not run.
    void writeFeatures(LoadedFrame& frame, const std::string& path,
        const std::vector<std::string>& inputs, Progress* progress);
    /// --preroll: run the filter on the frame to advance its history; nothing is kept or written.
    void advance(LoadedFrame& frame, Progress* progress) { run(frame, progress); }
    const std::string& method() const { return m_method; }
    /// The action with every parameter as the filter has it ("--denoise:method=svgf:alpha=0.2:
    /// ..."; ":weights=FILE" when given), for the outputs' history.
    std::string describe() const;
    /// A statistic of the last frame (afnGetFilterFloat), e.g. "stats.afn.prediction.ms".
    double statistic(const char* name) const { return m_filter.get<float>(name); }

private:
    void run(LoadedFrame& frame, Progress* progress);
    /// The frame's log: warnings when the inputs or afn's model fall short (once per change); the
    /// model, aux decision, speckle and skipped shares on the first frame and, with -v, on every
    /// frame; otherwise a line only when the model, aux decision or missing inputs change.
    void logFrame(const LoadedFrame& frame, Progress* progress);
    void check(const std::string& what, const std::string& file);
    /// Bind the :mask= channel of the frame (or unbind the mask); CliError when the file lacks it.
    void bindMask(const LoadedFrame& frame);
    /// Bind the :passes= light passes of the frame (denoised in place into frame.images.passes),
    /// or unbind those of the previous frame; CliError when the file lacks one.
    void bindPasses(LoadedFrame& frame, Progress* progress);
    /// --device cuda|auto: the filter on the CUDA device; with auto, nothing (the CPU is used)
    /// when there is no CUDA device or the method does not run there.
    void openOnCuda(const std::string& choice);

    const Options& m_opts;
    std::string m_flag; ///< "--denoise" or "--features", for messages
    bool m_features = false; ///< --features: bind the feature outputs instead of "output"
    bool m_hasSpp = false; ///< the method has an "spp" parameter (set from the file's header)
    bool m_hasAux = false; ///< the method has an "aux" parameter (it demodulates)
    std::string m_method;
    std::string m_weights; ///< --weights or :weights= file ("" = built in)
    std::map<std::string, std::string> m_params;
    afn::DeviceRef m_device;
    afn::FilterRef m_filter;
    std::vector<float> m_output;
    std::string m_missingWarned; ///< the missing inputs last warned about (warned once per change)
    std::string m_maskChannel; ///< :mask=CHANNEL, the work mask's channel ("" = none)
    std::vector<float> m_mask; ///< that channel of the current frame
    std::string m_passes = "none"; ///< :passes=all|none|NAME,... (light passes denoised too)
    std::vector<std::string> m_passesBound; ///< the passes bound for the current frame
    bool m_recompositionChecked = false; ///< the passes' sum was checked against the beauty
    std::string m_modelWarned; ///< afn: the model path last seen (a fallback is warned once)
    /// Model, aux decision and missing inputs last logged (none before the first frame's line).
    std::optional<std::string> m_factsLogged;
};

/// --compare REF: per-frame and mean metrics of the current beauty against the reference frames
/// (REF: a file or a frame pattern); printed by finish() as a table, or JSON with --json.
class SequenceComparer {
public:
    SequenceComparer(RunContext& ctx, const Action& action);
    ~SequenceComparer();
    void process(const LoadedFrame& frame, Progress* progress);
    void finish();

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// --benchmark:methods=a,b,... (with --compare REF --report DIR) or --benchmark:size=WxH,...:
/// run, time and score the methods, print a summary and write the report files.
int runBenchmark(const Options& opts, const Action& action);

} // namespace afntool
