// SPDX-License-Identifier: Apache-2.0
// afntool: oiiotool-style command line over afn's public APIs (libafn, afn_io, afn_color).
// Errors print "afntool ERROR: <what> (<file>)" on stderr and exit with 1; nothing half-written
// is left behind (every output is written atomically).
#include "arg_checks.h"
#include "cli_error.h"
#include "frame_loader.h"
#include "help_text.h"
#include "ops.h"
#include "options.h"
#include "preroll.h"
#include "progress.h"
#include "run_checks.h"

#include <cstdio>
#include <memory>

namespace afntool {

namespace {

bool needsAllChannels(const Options& opts)
{
    if (opts.keepAovs)
        return true;
    for (const Action& a : opts.actions)
        if (a.name == "contact-sheet")
            return true;
    return false;
}

int run(const Options& opts)
{
    if (opts.usage) {
        // No arguments: the usage lines on stdout and success, as oiiotool does.
        std::fputs(usageText().c_str(), stdout);
        return 0;
    }
    if (opts.help) {
        std::fputs(
            (opts.helpTopic.empty() ? helpText() : topicHelpText(opts.helpTopic)).c_str(), stdout);
        return 0;
    }
    if (opts.methods) {
        std::fputs(methodsText().c_str(), stdout);
        return 0;
    }
    if (opts.version) {
        std::printf("afntool %d.%d.%d\n", AFN_VERSION_MAJOR, AFN_VERSION_MINOR, AFN_VERSION_PATCH);
        return 0;
    }
    checkActionModifiers(opts);
    checkPrerollUse(opts);
    for (const Action& a : opts.actions)
        if (a.name == "benchmark")
            return runBenchmark(opts, a);
    const std::vector<FrameRef> frames = resolveFrames(opts);
    RunContext ctx(opts);

    bool infoOnly = !opts.actions.empty();
    for (const Action& a : opts.actions)
        infoOnly = infoOnly && a.name == "info";
    if (infoOnly) {
        runInfo(ctx, frames);
        return 0;
    }
    if (opts.actions.empty())
        throw CliError("nothing to do: give an action (--info, --denoise, -o, ...)");
    if (opts.inputs.size() != 1)
        throw CliError("processing takes exactly one input (file, pattern or dataset folder)");

    std::vector<std::string> inputPaths;
    for (const FrameRef& f : frames)
        inputPaths.push_back(f.path);

    std::unique_ptr<SequenceDenoiser> denoiser, featureWriter;
    for (const Action& a : opts.actions)
        if (a.name == "denoise" || a.name == "features") {
            auto& slot = a.name == "denoise" ? denoiser : featureWriter;
            if (slot)
                throw CliError("--" + a.name + " given twice");
            slot = std::make_unique<SequenceDenoiser>(opts, a);
        }
    std::unique_ptr<SequenceComparer> comparer;
    for (const Action& a : opts.actions)
        if (a.name == "compare") {
            if (comparer)
                throw CliError("--compare given twice");
            comparer = std::make_unique<SequenceComparer>(ctx, a);
        }

    // Before anything is read or written: nothing is overwritten that the run reads, outputs
    // can hold -d and --compression, temporal methods run forward in time.
    checkOutputs(opts, frames, filesRead(opts, frames));
    checkFrameOrder(opts, frames);

    const std::vector<FrameRef> preroll = resolvePrerollFrames(opts, frames);
    Progress progress(static_cast<int>(preroll.size() + frames.size()), opts.quiet);
    runPreroll(ctx, preroll, denoiser.get(), featureWriter.get(), progress);
    const bool keepAll = needsAllChannels(opts);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        progress.update(static_cast<int>(preroll.size() + i), frames[i].path);
        LoadedFrame frame = loadFrame(ctx, frames[i], keepAll);
        for (const std::string& w : frame.images.mapping.warnings)
            warn(w + " (" + frames[i].path + ")", opts.quiet, &progress);
        for (const Action& a : opts.actions) {
            if (a.name == "info") {
                runInfo(ctx, { frames[i] });
            } else if (a.name == "denoise") {
                denoiser->process(frame, &progress);
            } else if (a.name == "compare") {
                comparer->process(frame, &progress);
            } else {
                const std::string out = outputPath(
                    a.arg, frames[i], frames.size(), a.name == "output" ? "-o" : "--" + a.name);
                if (a.name == "output")
                    writeOutput(ctx, frame, out, inputPaths);
                else if (a.name == "features")
                    featureWriter->writeFeatures(frame, out, inputPaths, &progress);
                else if (a.name == "preview")
                    writePreview(ctx, frame, a, out, inputPaths);
                else
                    writeContactSheet(ctx, frame, a, out, inputPaths);
            }
        }
    }
    progress.update(static_cast<int>(preroll.size() + frames.size()), "done");
    progress.finish();
    if (comparer)
        comparer->finish();
    return 0;
}

} // namespace

} // namespace afntool

int main(int argc, char** argv)
{
    using afntool::CliError;
    try {
        const afntool::Options opts = afntool::parseCommandLine(argc, argv);
        return afntool::run(opts);
    } catch (const CliError& e) {
        if (e.file().empty())
            std::fprintf(stderr, "afntool ERROR: %s\n", e.what());
        else
            std::fprintf(stderr, "afntool ERROR: %s (%s)\n", e.what(), e.file().c_str());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "afntool ERROR: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "afntool ERROR: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "afntool ERROR: unknown failure\n");
    }
    return 1;
}
