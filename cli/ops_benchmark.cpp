// SPDX-License-Identifier: Apache-2.0
// --benchmark:methods=...: run each method (and each listed setting) over the sequence, time the
// denoise stage apart from file I/O, score every frame against --compare's references, and write
// the report (--report DIR). Modifiers: methods=ta,svgf/iterations=2,... repeat=N error=METRIC
// crop=X,Y,W,H crop-frames=F,G.
#include "ops.h"

#include "cli_error.h"
#include "progress.h"
#include "report.h"
#include "text.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

namespace afntool {

int runSizeBenchmark(const Options& opts, const Action& action); // ops_benchmark_size.cpp

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

int toInt(const std::string& text, const std::string& what)
{
    try {
        std::size_t used = 0;
        const int v = std::stoi(text, &used);
        if (used == text.size())
            return v;
    } catch (const std::exception&) {
    }
    throw CliError("--benchmark: " + what + " expects an integer, got '" + text + "'");
}

std::string modifier(const Action& a, const std::string& key, const std::string& def = {})
{
    auto it = a.mods.find(key);
    return it == a.mods.end() ? def : it->second;
}

/// The command line of this process (for the report), from /proc; "" where unavailable.
std::string commandLine()
{
    std::ifstream f("/proc/self/cmdline", std::ios::binary);
    std::string all((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    for (char& c : all)
        if (c == '\0')
            c = ' ';
    while (!all.empty() && all.back() == ' ')
        all.pop_back();
    return all;
}

void finishTimes(MethodResult& m, const std::vector<double>& times, const std::vector<double>& cpu)
{
    m.medianMs = median(times);
    m.medianCpuMs = median(cpu);
    double sum = 0.0, minMs = std::numeric_limits<double>::infinity();
    for (double t : times)
        sum += t, minMs = std::min(minMs, t);
    m.meanMs = times.empty() ? 0.0 : sum / times.size();
    m.minMs = times.empty() ? 0.0 : minMs;
    m.means = sequenceMeans(m.frames);
}

/// A rectangle of a packed RGB image, through the display transform, written as PNG.
void writeCrop(RunContext& ctx, const std::vector<float>& rgb, int width, const CropSet& c,
    const std::string& path, const std::vector<std::string>& inputs)
{
    std::vector<float> crop(static_cast<std::size_t>(c.width) * c.height * 3);
    for (int y = 0; y < c.height; ++y)
        std::copy_n(&rgb[((static_cast<std::size_t>(c.y) + y) * width + c.x) * 3], c.width * 3,
            &crop[static_cast<std::size_t>(y) * c.width * 3]);
    try {
        ctx.color().toDisplay(crop.data(), c.width, c.height, 3, {});
        afn::io::WriteOptions wo;
        wo.inputs = inputs;
        afn::io::writeImageAtomic(path, c.width, c.height, { "R", "G", "B" }, crop.data(), wo);
    } catch (const afn::color::ColorError& e) {
        throw CliError(std::string("--report crop: ") + e.what(), path);
    } catch (const afn::io::IoError& e) {
        throw CliError(e.what(), e.file().empty() ? path : e.file());
    }
}

std::string fileLabel(const std::string& label)
{
    std::string s;
    for (char c : label)
        s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return s;
}

void printSummary(const BenchmarkReport& r, double ioMsPerFrame)
{
    std::printf("%-24s %10s %10s %10s %8s %8s %8s %10s\n", "method", "ms/frame", "cpu ms",
        "PSNR(dB)", "SSIM", "RMSE", "SMAPE", "tge");
    auto row = [](const MethodResult& m, bool timed) {
        char ms[32] = "-", cpu[32] = "-";
        if (timed)
            std::snprintf(ms, sizeof ms, "%.2f", m.medianMs);
        if (timed)
            std::snprintf(cpu, sizeof cpu, "%.2f", m.medianCpuMs);
        std::printf("%-24s %10s %10s %10.3f %8.4f %8.4f %8.4f %10.5f\n", m.label.c_str(), ms, cpu,
            m.means.at("psnr"), m.means.at("ssim"), m.means.at("rmse"), m.means.at("smape"),
            m.means.at("tge"));
    };
    if (!r.noisy.label.empty())
        row(r.noisy, false);
    for (const MethodResult& m : r.methods)
        row(m, true);
    std::printf("(median denoise-stage ms per frame over %d frame(s) x %d run(s); file I/O %.1f ms "
                "per frame, not included)\n",
        r.frameCount, r.repeat, ioMsPerFrame);
}

} // namespace

MethodResult parseSetting(const std::string& item)
{
    MethodResult m;
    m.label = item;
    const std::vector<std::string> parts = splitList(item, '/');
    m.method = parts.empty() ? "" : parts[0];
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const std::size_t eq = parts[i].find('=');
        if (eq == std::string::npos || eq == 0)
            throw CliError(
                "--benchmark: malformed setting '" + item + "' (expected method/param=value)");
        m.params[parts[i].substr(0, eq)] = parts[i].substr(eq + 1);
    }
    return m;
}

int runBenchmark(const Options& opts, const Action& action)
{
    if (action.mods.count("size"))
        return runSizeBenchmark(opts, action);
    const std::string methodsText = modifier(action, "methods");
    if (methodsText.empty())
        throw CliError("--benchmark needs :methods=a,b,... or :size=WxH,... (see afntool --help)");
    std::string refPattern;
    for (const Action& a : opts.actions)
        if (a.name == "compare")
            refPattern = a.arg;
    if (refPattern.empty())
        throw CliError("--benchmark:methods needs --compare REF (the references)");

    BenchmarkReport report;
    report.commandLine = commandLine();
    report.input = opts.inputs.empty() ? "" : opts.inputs.front();
    report.reference = refPattern;
    report.threads = opts.threads;
    report.hardwareThreads = std::thread::hardware_concurrency();
    report.repeat = std::max(1, toInt(modifier(action, "repeat", "1"), "repeat"));
    report.errorMetric = metricColumn(modifier(action, "error", "rmse")).name;

    // Settings to run; unknown methods are skipped with a warning.
    const std::vector<std::string> known = afn::filterTypes();
    std::vector<MethodResult> settings;
    for (const std::string& item : splitList(methodsText, ',')) {
        MethodResult m = parseSetting(item);
        if (std::find(known.begin(), known.end(), m.method) == known.end()) {
            report.warnings.push_back("method '" + m.method + "' is not in this build; skipped");
            warn(report.warnings.back(), opts.quiet);
            continue;
        }
        settings.push_back(m);
    }
    if (settings.empty())
        throw CliError("--benchmark: none of the methods '" + methodsText + "' exists");

    // File I/O, timed apart: every input frame and reference, loaded once.
    RunContext ctx(opts);
    const std::vector<FrameRef> refs = resolveFrames(opts);
    std::vector<LoadedFrame> frames, references;
    std::vector<std::string> inputPaths;
    const Clock::time_point io0 = Clock::now();
    for (const FrameRef& f : refs) {
        frames.push_back(loadFrame(ctx, f, false));
        inputPaths.push_back(f.path);
        std::string rp = refPattern;
        if (afn::io::hasFramePattern(refPattern)) {
            if (!f.numbered)
                throw CliError("--compare has a frame pattern but the input is a single file", rp);
            rp = afn::io::expandFramePattern(refPattern, f.frame);
        }
        references.push_back(loadFrame(ctx, { rp, f.frame }, false));
        inputPaths.push_back(rp);
    }
    report.ioMsPerFrame = msSince(io0) / std::max<std::size_t>(1, refs.size());
    const afn::io::RoleImage& c0 = frames.front().images.roles.at(afn::io::Role::Color);
    const int w = c0.width, h = c0.height;
    report.width = w;
    report.height = h;
    report.frameCount = static_cast<int>(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const afn::io::RoleImage& c = frames[i].images.roles.at(afn::io::Role::Color);
        const afn::io::RoleImage& r = references[i].images.roles.at(afn::io::Role::Color);
        if (c.width != w || c.height != h || r.width != w || r.height != h)
            throw CliError("--benchmark: every frame and reference must be " + std::to_string(w)
                    + "x" + std::to_string(h),
                references[i].ref.path);
    }

    // Crop frames and rectangle (default: the last frame, a centred square of up to 128 pixels).
    std::vector<int> cropIdx;
    for (const std::string& s : splitList(modifier(action, "crop-frames"), ',')) {
        const int f = toInt(s, "crop-frames");
        for (std::size_t i = 0; i < frames.size(); ++i)
            if (frames[i].ref.frame == f)
                cropIdx.push_back(static_cast<int>(i));
    }
    if (cropIdx.empty())
        cropIdx.push_back(static_cast<int>(frames.size()) - 1);
    CropSet rect;
    const std::vector<std::string> cr = splitList(modifier(action, "crop"), ',');
    if (cr.size() == 4) {
        rect.x = toInt(cr[0], "crop"), rect.y = toInt(cr[1], "crop");
        rect.width = toInt(cr[2], "crop"), rect.height = toInt(cr[3], "crop");
    } else if (!cr.empty()) {
        throw CliError("--benchmark: crop expects X,Y,W,H");
    } else {
        rect.width = std::min(w, 128), rect.height = std::min(h, 128);
        rect.x = (w - rect.width) / 2, rect.y = (h - rect.height) / 2;
    }
    if (rect.x < 0 || rect.y < 0 || rect.width <= 0 || rect.height <= 0 || rect.x + rect.width > w
        || rect.y + rect.height > h)
        throw CliError("--benchmark: crop rectangle outside the " + std::to_string(w) + "x"
            + std::to_string(h) + " frame");

    // The noisy input scored as a baseline (not when the beauty is albedo-demodulated).
    SequenceEvaluator evaluator(opts.threads);
    if (!frames.front().images.mapping.tag.colorDemodulated) {
        report.noisy.label = "noisy input";
        for (std::size_t i = 0; i < frames.size(); ++i)
            report.noisy.frames.push_back(evaluator.evaluate(frames[i].ref.frame, frames[i].beauty,
                references[i].beauty, w, h, frames[i].ref.path));
        finishTimes(report.noisy, {}, {});
    }

    Progress progress(
        static_cast<int>(settings.size() * report.repeat * frames.size()), opts.quiet);
    int done = 0;
    std::vector<std::vector<std::vector<float>>> cropImages; // [method][crop frame]: outputs
    for (MethodResult& m : settings) {
        Action denoise { "denoise", "", m.params };
        denoise.mods["method"] = m.method;
        std::vector<double> times, cpuTimes;
        std::vector<std::vector<float>> crops;
        try {
            for (int rep = 0; rep < report.repeat; ++rep) {
                SequenceDenoiser denoiser(opts, denoise); // fresh history per run
                const bool last = rep + 1 == report.repeat;
                if (last)
                    evaluator.restart();
                for (std::size_t i = 0; i < frames.size(); ++i) {
                    progress.update(done++, m.label + " " + frames[i].ref.path);
                    LoadedFrame frame = frames[i]; // copy outside the timed stage
                    const double cpu0 = processCpuMs();
                    const Clock::time_point t0 = Clock::now();
                    denoiser.process(frame, &progress);
                    const double ms = msSince(t0), cpuMs = processCpuMs() - cpu0;
                    times.push_back(ms);
                    cpuTimes.push_back(cpuMs);
                    if (!last)
                        continue;
                    FrameResult r = evaluator.evaluate(
                        frame.ref.frame, frame.beauty, references[i].beauty, w, h, frame.ref.path);
                    r.ms = ms;
                    r.cpuMs = cpuMs;
                    m.frames.push_back(r);
                    if (std::find(cropIdx.begin(), cropIdx.end(), static_cast<int>(i))
                        != cropIdx.end())
                        crops.push_back(frame.beauty);
                }
            }
        } catch (const CliError& e) {
            // One method failing (e.g. "afn" without weights) does not end the benchmark.
            report.warnings.push_back(
                "method '" + m.label + "' failed and is left out: " + e.what());
            warn(report.warnings.back(), opts.quiet, &progress);
            continue;
        }
        finishTimes(m, times, cpuTimes);
        report.methods.push_back(m);
        cropImages.push_back(std::move(crops));
    }
    progress.update(done, "done");
    progress.clear();
    if (report.methods.empty())
        throw CliError("--benchmark: every method failed (see the warnings)");

    if (!opts.report.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(opts.report, ec);
        if (ec)
            throw CliError("cannot create the report folder: " + ec.message(), opts.report);
        for (std::size_t k = 0; k < cropIdx.size(); ++k) {
            const int i = cropIdx[k];
            CropSet c = rect;
            c.frame = frames[i].ref.frame;
            const std::string stem = "crop_f" + std::to_string(c.frame) + "_";
            auto add = [&](const std::string& label, const std::vector<float>& rgb) {
                const std::string file = stem + fileLabel(label) + ".png";
                writeCrop(ctx, rgb, w, c, opts.report + "/" + file, inputPaths);
                c.images.emplace_back(label, file);
            };
            // The reference first (what the others are judged against), then the input.
            add("reference", references[i].beauty);
            add("noisy input", frames[i].beauty);
            for (std::size_t s = 0; s < report.methods.size(); ++s)
                add(report.methods[s].label, cropImages[s][k]);
            report.crops.push_back(c);
        }
        writeResultsJson(opts.report, report);
        writeResultsCsv(opts.report, report);
        writeTextAtomic(opts.report + "/runtime-vs-error.svg", runtimeErrorSvg(report));
        writeIndexHtml(opts.report, report);
    }
    printSummary(report, report.ioMsPerFrame);
    if (!opts.report.empty())
        std::printf("report: %s/index.html\n", opts.report.c_str());
    return 0;
}

} // namespace afntool
