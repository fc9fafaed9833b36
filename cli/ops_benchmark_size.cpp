// SPDX-License-Identifier: Apache-2.0
// --benchmark:size=1280x720,1920x1080,...: time the denoise stage alone on generated inputs of each
// size, for scaling curves (time against pixel count). Modifiers: methods=a,b (default: every type
// but "identity"; settings as method/param=value, e.g. afn/quality=fast), frames=N timed frames
// (default 5) after warmup=W untimed ones (default 2), rounds=R repetitions of the whole sweep
// (default 1; sizes and methods alternate, the medians are over all rounds' frames, so that a
// shared host's slow minutes fall on every size alike).
// Per point also the peak heap of the run (heap_counter.h: every operator new of the process,
// filter creation to the last frame; the generated input frame, allocated before, is left out),
// and for afn the engine report (engine_report.h: GFLOP/s per stage beside dnnl_sgemm).
// The inputs are plain fills plus hashed per-pixel noise (benchmark_frame.h). With :sky=S the
// work-skipping benchmark runs instead (ops_benchmark_skip.cpp).
#include "ops.h"

#include "benchmark_frame.h"
#include "cli_error.h"
#include "engine_report.h"
#include "heap_counter.h"
#include "json_writer.h"
#include "progress.h"
#include "report.h"
#include "text.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace afntool {

namespace {

struct SizePoint {
    std::string method;
    int width = 0, height = 0;
    double medianMs = 0.0;
    double msPerMegapixel = 0.0;
    double medianCpuMs = 0.0; ///< process CPU time, all threads
    double cpuMsPerMegapixel = 0.0;
    double heapPeakMiB = 0.0; ///< peak heap of the run above what was live before it
    int frames = 0; ///< timed frames of all rounds behind the medians
};

std::pair<int, int> parseSize(const std::string& text)
{
    const std::size_t x = text.find('x');
    try {
        if (x != std::string::npos) {
            const int w = std::stoi(text.substr(0, x)), h = std::stoi(text.substr(x + 1));
            if (w > 0 && h > 0 && w <= 16384 && h <= 16384)
                return { w, h };
        }
    } catch (const std::exception&) {
    }
    throw CliError("--benchmark: size expects WIDTHxHEIGHT (1..16384), got '" + text + "'");
}

} // namespace

int runSkyBenchmark(const Options& opts, const Action& action); // ops_benchmark_skip.cpp

int runSizeBenchmark(const Options& opts, const Action& action)
{
    if (action.mods.count("sky"))
        return runSkyBenchmark(opts, action);
    auto mod = [&](const char* k, const std::string& def) {
        auto it = action.mods.find(k);
        return it == action.mods.end() ? def : it->second;
    };
    std::vector<std::pair<int, int>> sizes;
    for (const std::string& s : splitList(mod("size", ""), ','))
        sizes.push_back(parseSize(s));
    if (sizes.empty())
        throw CliError("--benchmark:size needs at least one WIDTHxHEIGHT");
    const std::vector<std::string> known = afn::filterTypes();
    std::vector<std::string> methods;
    for (const std::string& m : splitList(mod("methods", ""), ',')) {
        const std::string type = parseSetting(m).method; // "afn/quality=fast": a setting of afn
        if (std::find(known.begin(), known.end(), type) == known.end())
            warn("method '" + type + "' is not in this build; skipped", opts.quiet);
        else
            methods.push_back(m);
    }
    if (mod("methods", "").empty())
        for (const std::string& m : known)
            if (m != "identity")
                methods.push_back(m);
    if (methods.empty())
        throw CliError("--benchmark:size: no method to time");
    int timed = 5, warmup = 2, rounds = 1;
    try {
        timed = std::max(1, std::stoi(mod("frames", "5")));
        warmup = std::max(0, std::stoi(mod("warmup", "2")));
        rounds = std::max(1, std::stoi(mod("rounds", "1")));
    } catch (const std::exception&) {
        throw CliError("--benchmark: frames, warmup and rounds expect integers");
    }

    // The yardstick first (afn only), so that its threads are idle again when afn runs.
    const bool engine = std::find(methods.begin(), methods.end(), "afn") != methods.end()
        && opts.device != "cuda";
    EngineYardstick yardstick;
    if (engine)
        yardstick = measureYardstick(opts.threads);

    // Per (size, method): every timed frame of every round. Rounds repeat the whole sweep, so
    // each size sees the same minutes of a shared host; the medians are over all rounds' frames.
    struct Run {
        std::vector<double> times, cpuTimes;
        double heapPeakMiB = 0.0;
        EngineCollector collector;
        bool failed = false;
    };
    std::vector<Run> runs(sizes.size() * methods.size());
    Progress progress(static_cast<int>(sizes.size() * methods.size()) * rounds, opts.quiet);
    int done = 0;
    for (int round = 0; round < rounds; ++round)
        for (std::size_t si = 0; si < sizes.size(); ++si) {
            const auto [w, h] = sizes[si];
            LoadedFrame frame;
            makeFrame(frame, w, h, 0); // allocated before the heap baseline of each run
            for (std::size_t mi = 0; mi < methods.size(); ++mi) {
                const std::string& m = methods[mi];
                Run& run = runs[si * methods.size() + mi];
                progress.update(done++, m + " " + std::to_string(w) + "x" + std::to_string(h));
                if (run.failed)
                    continue;
                const MethodResult setting = parseSetting(m);
                Action denoise { "denoise", "", setting.params };
                denoise.mods["method"] = setting.method;
                heap::resetPeak();
                const std::size_t heapBase = heap::liveBytes();
                try {
                    SequenceDenoiser denoiser(opts, denoise);
                    for (int i = 0; i < warmup + timed; ++i) {
                        makeFrame(frame, w, h, i);
                        const double cpu0 = processCpuMs();
                        const auto t0 = std::chrono::steady_clock::now();
                        denoiser.process(frame, &progress);
                        const double ms = std::chrono::duration<double, std::milli>(
                            std::chrono::steady_clock::now() - t0)
                                              .count();
                        if (i < warmup)
                            continue;
                        run.times.push_back(ms);
                        run.cpuTimes.push_back(processCpuMs() - cpu0);
                        if (m == "afn" && engine)
                            run.collector.add([&](const char* s) { return denoiser.statistic(s); });
                    }
                } catch (const CliError& e) {
                    // One method failing (e.g. "afn" without weights) does not end the benchmark.
                    warn("method '" + m + "' failed at " + std::to_string(w) + "x"
                            + std::to_string(h) + " and is left out: " + e.what(),
                        opts.quiet, &progress);
                    run.failed = true;
                    continue;
                }
                run.heapPeakMiB = std::max(
                    run.heapPeakMiB, static_cast<double>(heap::peakBytes() - heapBase) / (1 << 20));
            }
        }
    std::vector<SizePoint> points;
    std::vector<EnginePoint> enginePoints;
    for (std::size_t si = 0; si < sizes.size(); ++si)
        for (std::size_t mi = 0; mi < methods.size(); ++mi) {
            const Run& run = runs[si * methods.size() + mi];
            if (run.failed || run.times.empty())
                continue;
            const auto [w, h] = sizes[si];
            const std::string& m = methods[mi];
            SizePoint p { m, w, h, median(run.times), 0.0, median(run.cpuTimes), 0.0 };
            p.heapPeakMiB = run.heapPeakMiB;
            p.frames = static_cast<int>(run.times.size());
            if (m == "afn" && engine)
                enginePoints.push_back(run.collector.finish(w, h));
            p.msPerMegapixel = p.medianMs / (static_cast<double>(w) * h / 1e6);
            p.cpuMsPerMegapixel = p.medianCpuMs / (static_cast<double>(w) * h / 1e6);
            points.push_back(p);
        }
    progress.clear();

    // Linearity: ms per megapixel relative to the first listed size of the same method.
    auto base = [&](const std::string& m) -> const SizePoint& {
        for (const SizePoint& p : points)
            if (p.method == m)
                return p;
        return points.front();
    };
    JsonWriter j;
    j.beginObject()
        .field("timedFrames", timed)
        .field("warmupFrames", warmup)
        .field("rounds", rounds)
        .field("threads", opts.threads)
        .field("device", opts.device);
    j.key("points").beginArray();
    std::ostringstream csv;
    csv << "method,width,height,megapixels,medianMs,msPerMegapixel,relativeToFirst,medianCpuMs,"
           "cpuMsPerMegapixel,cpuRelativeToFirst,heapPeakMiB,heapMiBPerMegapixel\n";
    if (!opts.json)
        std::printf("%-8s %11s %6s %11s %9s %6s %11s %9s %6s %9s %9s\n", "method", "size", "MP",
            "ms/frame", "ms/MP", "rel.", "cpu ms", "cpu ms/MP", "rel.", "heap MiB", "MiB/MP");
    for (const SizePoint& p : points) {
        const double mp = static_cast<double>(p.width) * p.height / 1e6;
        const double rel = p.msPerMegapixel / base(p.method).msPerMegapixel;
        const double relCpu = p.cpuMsPerMegapixel / base(p.method).cpuMsPerMegapixel;
        if (!opts.json)
            std::printf("%-8s %5dx%-5d %6.2f %11.2f %9.2f %6.3f %11.2f %9.2f %6.3f %9.1f %9.1f\n",
                p.method.c_str(), p.width, p.height, mp, p.medianMs, p.msPerMegapixel, rel,
                p.medianCpuMs, p.cpuMsPerMegapixel, relCpu, p.heapPeakMiB, p.heapPeakMiB / mp);
        j.beginObject().field("method", p.method).field("width", p.width).field("height", p.height);
        j.field("megapixels", mp)
            .field("medianMs", p.medianMs)
            .field("msPerMegapixel", p.msPerMegapixel);
        j.field("relativeToFirst", rel).field("medianCpuMs", p.medianCpuMs);
        j.field("cpuMsPerMegapixel", p.cpuMsPerMegapixel).field("cpuRelativeToFirst", relCpu);
        j.field("heapPeakMiB", p.heapPeakMiB).field("heapMiBPerMegapixel", p.heapPeakMiB / mp);
        j.field("frames", p.frames);
        j.endObject();
        char line[320];
        std::snprintf(line, sizeof line, "%s,%d,%d,%.6f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f,%.2f\n",
            p.method.c_str(), p.width, p.height, mp, p.medianMs, p.msPerMegapixel, rel,
            p.medianCpuMs, p.cpuMsPerMegapixel, relCpu, p.heapPeakMiB, p.heapPeakMiB / mp);
        csv << line;
    }
    j.endArray();
    if (engine)
        writeEngineJson(j, yardstick, enginePoints);
    j.endObject();
    if (opts.json)
        std::printf("%s\n", j.str().c_str());
    else
        std::printf("(median of %d timed frames after %d warm-up frames, over %d round(s) of "
                    "the whole sweep, on --device %s; rel. = per-megapixel time against the "
                    "method's first size: 1.0 = linear in pixel count; cpu = process CPU time of "
                    "all threads; heap = peak operator-new bytes of the run, input frame "
                    "excluded)\n",
            timed, warmup, rounds, opts.device.c_str());
    if (!opts.json && engine)
        printEngineReport(yardstick, enginePoints);
    if (!opts.report.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(opts.report, ec);
        if (ec)
            throw CliError("cannot create the report folder: " + ec.message(), opts.report);
        writeTextAtomic(opts.report + "/scaling.json", j.str() + "\n");
        writeTextAtomic(opts.report + "/scaling.csv", csv.str());
        if (engine)
            writeTextAtomic(opts.report + "/engine.csv", engineCsv(yardstick, enginePoints));
    }
    return 0;
}

} // namespace afntool
