// SPDX-License-Identifier: Apache-2.0
// --benchmark:size=WxH:sky=S: what work skipping buys. Per method, on generated frames
// (benchmark_frame.h) of one size, three runs of warmup + frames each: "full" (every pixel
// covered by geometry), "sky" (the top S of the rows sky, depth 1e10, skip on: the default) and
// "sky skip=off" (the same frames, every pixel denoised). Reported: median wall and process-CPU ms
// per frame, the ratios sky / full and sky / sky skip=off, and the largest difference between
// the two sky runs over the covered pixels on every timed frame (0 = bit-identical: skipping
// changed no pixel that needed denoising) and the covered rows' PSNR against their noiseless
// value (benchmark_frame.h kCoveredExpectation) in all three runs. rounds=N repeats the three runs
// alternately and takes the medians over all rounds' frames (robust on a shared machine).
// Modifiers: methods=a,b (default every type but identity), frames=N (5), warmup=W (2), rounds=R
// (1).
#include "ops.h"

#include "benchmark_frame.h"
#include "cli_error.h"
#include "json_writer.h"
#include "progress.h"
#include "report.h"
#include "text.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace afntool {

namespace {

struct SkipRun {
    std::vector<double> ms, cpuMs;
    std::vector<std::vector<float>> outputs; ///< per timed frame of the last round
};

enum Case { kFull, kSky, kSkyOff, kCases };
const char* const kCaseNames[kCases] = { "full", "sky", "sky skip=off" };

/// Run one case: a fresh denoiser over warmup + timed generated frames.
void runCase(const Options& opts, const std::string& method, int w, int h, double sky, bool skip,
    int warmup, int timed, Progress& progress, SkipRun& run)
{
    Action denoise { "denoise", "", { { "method", method }, { "skip", skip ? "on" : "off" } } };
    SequenceDenoiser denoiser(opts, denoise);
    LoadedFrame frame;
    run.outputs.clear();
    for (int i = 0; i < warmup + timed; ++i) {
        makeFrame(frame, w, h, i, sky);
        const double cpu0 = processCpuMs();
        const auto t0 = std::chrono::steady_clock::now();
        denoiser.process(frame, &progress);
        const double ms
            = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                  .count();
        if (i < warmup)
            continue;
        run.ms.push_back(ms);
        run.cpuMs.push_back(processCpuMs() - cpu0);
        run.outputs.push_back(frame.beauty);
    }
}

/// Largest |a - b| over rows [y0, h) of every frame pair (NaN counts as infinite).
double coveredDifference(const SkipRun& a, const SkipRun& b, int w, int y0)
{
    double worst = 0.0;
    for (std::size_t f = 0; f < a.outputs.size() && f < b.outputs.size(); ++f)
        for (std::size_t i = static_cast<std::size_t>(y0) * w * 3; i < a.outputs[f].size(); ++i) {
            const double d = std::fabs(static_cast<double>(a.outputs[f][i]) - b.outputs[f][i]);
            worst = std::isnan(d) ? INFINITY : std::max(worst, d);
        }
    return worst;
}

/// PSNR (peak 1) over rows [y0, h) of every timed frame against kCoveredExpectation, the
/// generated frames' noiseless covered value (benchmark_frame.h).
double coveredPsnr(const SkipRun& r, int w, int y0)
{
    double se = 0.0;
    std::size_t n = 0;
    for (const std::vector<float>& out : r.outputs)
        for (std::size_t i = static_cast<std::size_t>(y0) * w * 3; i < out.size(); ++i, ++n) {
            const double d = static_cast<double>(out[i]) - kCoveredExpectation;
            se += d * d;
        }
    return n == 0 || se == 0.0 ? INFINITY : -10.0 * std::log10(se / static_cast<double>(n));
}

int toCount(const std::string& text, const char* what, int lo)
{
    try {
        return std::max(lo, std::stoi(text));
    } catch (const std::exception&) {
        throw CliError(
            std::string("--benchmark: ") + what + " expects an integer, got '" + text + "'");
    }
}

} // namespace

int runSkyBenchmark(const Options& opts, const Action& action)
{
    auto mod = [&](const char* k, const std::string& def) {
        auto it = action.mods.find(k);
        return it == action.mods.end() ? def : it->second;
    };
    const std::vector<std::string> sizes = splitList(mod("size", ""), ',');
    if (sizes.size() != 1)
        throw CliError("--benchmark:sky takes one size (e.g. :size=1280x720:sky=0.6)");
    const std::size_t x = sizes[0].find('x');
    int w = 0, h = 0;
    try {
        w = std::stoi(sizes[0].substr(0, x)), h = std::stoi(sizes[0].substr(x + 1));
    } catch (const std::exception&) {
    }
    if (x == std::string::npos || w <= 0 || h <= 0 || w > 16384 || h > 16384)
        throw CliError("--benchmark: size expects WIDTHxHEIGHT (1..16384), got '" + sizes[0] + "'");
    double sky = -1.0;
    try {
        sky = std::stod(mod("sky", ""));
    } catch (const std::exception&) {
    }
    if (!(sky > 0.0 && sky < 1.0))
        throw CliError("--benchmark: sky expects the share of sky rows in (0, 1), got '"
            + mod("sky", "") + "'");
    const int timed = toCount(mod("frames", "5"), "frames", 1);
    const int warmup = toCount(mod("warmup", "2"), "warmup", 0);
    const int rounds = toCount(mod("rounds", "1"), "rounds", 1);
    const std::vector<std::string> known = afn::filterTypes();
    std::vector<std::string> methods = splitList(mod("methods", ""), ',');
    if (methods.empty())
        for (const std::string& m : known)
            if (m != "identity")
                methods.push_back(m);
    for (const std::string& m : methods)
        if (std::find(known.begin(), known.end(), m) == known.end())
            throw CliError("--benchmark: method '" + m + "' is not in this build");

    const int covered = skyRows(h, sky);
    JsonWriter j;
    j.beginObject().field("width", w).field("height", h).field("sky", sky);
    j.field("timedFrames", timed).field("warmupFrames", warmup).field("rounds", rounds);
    j.field("threads", opts.threads);
    j.key("methods").beginArray();
    std::ostringstream csv;
    csv << "method,width,height,sky,fullMs,skyMs,skyOffMs,skyOverFull,skyOverSkyOff,fullCpuMs,"
           "skyCpuMs,skyOffCpuMs,cpuSkyOverFull,cpuSkyOverSkyOff,coveredMaxDiff,coveredPsnrSky,"
           "coveredPsnrSkyOff,coveredPsnrFull\n";
    if (!opts.json)
        std::printf("%-6s %9s %9s %9s %8s %8s %9s %9s %8s %8s %12s %9s %9s\n", "method", "full ms",
            "sky ms", "off ms", "sky/full", "sky/off", "full cpu", "sky cpu", "sky/full", "sky/off",
            "covered diff", "psnr sky", "off-sky");
    Progress progress(static_cast<int>(methods.size()) * rounds * kCases, opts.quiet);
    int done = 0;
    for (const std::string& m : methods) {
        SkipRun runs[kCases];
        try {
            for (int r = 0; r < rounds; ++r)
                for (int c = 0; c < kCases; ++c) {
                    progress.update(done++, m + " " + kCaseNames[c]);
                    runCase(opts, m, w, h, c == kFull ? 0.0 : sky, c != kSkyOff, warmup, timed,
                        progress, runs[c]);
                }
        } catch (const CliError& e) {
            warn("method '" + m + "' failed and is left out: " + e.what(), opts.quiet, &progress);
            continue;
        }
        double ms[kCases], cpu[kCases];
        for (int c = 0; c < kCases; ++c)
            ms[c] = median(runs[c].ms), cpu[c] = median(runs[c].cpuMs);
        const double diff = coveredDifference(runs[kSky], runs[kSkyOff], w, covered);
        double psnr[kCases];
        for (int c = 0; c < kCases; ++c)
            psnr[c] = coveredPsnr(runs[c], w, covered);
        if (!opts.json)
            std::printf("%-6s %9.1f %9.1f %9.1f %8.3f %8.3f %9.1f %9.1f %8.3f %8.3f %12.3g %9.3f "
                        "%9.3f\n",
                m.c_str(), ms[kFull], ms[kSky], ms[kSkyOff], ms[kSky] / ms[kFull],
                ms[kSky] / ms[kSkyOff], cpu[kFull], cpu[kSky], cpu[kSky] / cpu[kFull],
                cpu[kSky] / cpu[kSkyOff], diff, psnr[kSky], psnr[kSkyOff] - psnr[kSky]);
        j.beginObject().field("method", m).field("fullMs", ms[kFull]).field("skyMs", ms[kSky]);
        j.field("skyOffMs", ms[kSkyOff]).field("fullCpuMs", cpu[kFull]);
        j.field("skyCpuMs", cpu[kSky]).field("skyOffCpuMs", cpu[kSkyOff]);
        j.field("coveredMaxDiff", diff).field("coveredPsnrSky", psnr[kSky]);
        j.field("coveredPsnrSkyOff", psnr[kSkyOff]).field("coveredPsnrFull", psnr[kFull]);
        j.endObject();
        char line[400];
        std::snprintf(line, sizeof line,
            "%s,%d,%d,%.3f,%.3f,%.3f,%.3f,%.4f,%.4f,%.3f,%.3f,%.3f,%.4f,%.4f,%.6g,%.4f,%.4f,%.4f\n",
            m.c_str(), w, h, sky, ms[kFull], ms[kSky], ms[kSkyOff], ms[kSky] / ms[kFull],
            ms[kSky] / ms[kSkyOff], cpu[kFull], cpu[kSky], cpu[kSkyOff], cpu[kSky] / cpu[kFull],
            cpu[kSky] / cpu[kSkyOff], diff, psnr[kSky], psnr[kSkyOff], psnr[kFull]);
        csv << line;
    }
    progress.clear();
    j.endArray().endObject();
    if (opts.json)
        std::printf("%s\n", j.str().c_str());
    else
        std::printf(
            "(median ms per frame over %d round(s) of %d timed frames after %d warm-up "
            "frames; full = every pixel covered, sky = top %.0f %% of the rows sky with "
            "skip on, off = the same with skip=off; covered diff = largest |sky - off| on "
            "the covered rows, 0 = bit-identical; psnr sky = PSNR (peak 1) of the covered rows "
            "against their noiseless value, off-sky = the same with skip=off minus it, "
            "in dB)\n",
            rounds, timed, warmup, 100.0 * sky);
    if (!opts.report.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(opts.report, ec);
        if (ec)
            throw CliError("cannot create the report folder: " + ec.message(), opts.report);
        writeTextAtomic(opts.report + "/skip.json", j.str() + "\n");
        writeTextAtomic(opts.report + "/skip.csv", csv.str());
    }
    return 0;
}

} // namespace afntool
