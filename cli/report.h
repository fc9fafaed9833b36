// SPDX-License-Identifier: Apache-2.0
// Evaluation results of afntool --compare and --benchmark, and the files that report them
// (results.json, results.csv, runtime-vs-error.svg, index.html). Metric definitions:
// docs/metrics.md.
#pragma once

#include "afn/afn.hpp"

#include <map>
#include <string>
#include <vector>

namespace afntool {

/// Metrics of one frame; `hasTemporal` is false for the first frame of a sequence.
struct FrameResult {
    int frame = -1;
    double ms = 0.0; ///< denoise-stage wall time of this frame (benchmark only), milliseconds
    double cpuMs = 0.0; ///< process CPU time (all threads) of the same stage, milliseconds
    AFNMetrics metrics {};
    bool hasTemporal = false;
    AFNTemporalMetrics temporal {};
};

/// One metric column: name, label and how to read it from a FrameResult.
struct MetricColumn {
    const char* name; ///< JSON/CSV key ("psnr", "ssim", ...)
    const char* label; ///< table header
    bool higherIsBetter;
    bool temporal; ///< only defined from the second frame on
    double (*get)(const FrameResult&);
};

/// Every metric afntool reports, in report order.
const std::vector<MetricColumn>& metricColumns();
/// The column with that name; throws CliError listing the names if unknown.
const MetricColumn& metricColumn(const std::string& name);

/// Per-sequence values: the mean of the per-frame values of each metric (temporal ones over the
/// frames that have them). NaN frames make the mean NaN (never skipped).
std::map<std::string, double> sequenceMeans(const std::vector<FrameResult>& frames);

/// Evaluates a sequence frame by frame: metrics against the reference, and the temporal-gradient
/// error against the previous frame of the same sequence.
class SequenceEvaluator {
public:
    explicit SequenceEvaluator(int threads);
    /// `test`, `reference`: packed RGB, width*height*3 floats, same size; `file` names errors.
    FrameResult evaluate(int frame, const std::vector<float>& test,
        const std::vector<float>& reference, int width, int height, const std::string& file);
    /// Forget the previous frame (a new sequence starts).
    void restart() { m_prevTest.clear(); }

private:
    afn::DeviceRef m_device;
    std::vector<float> m_prevTest, m_prevRef;
};

/// One run of a method (or the noisy input) over the sequence.
struct MethodResult {
    std::string label; ///< "svgf" or "svgf/iterations=2"
    std::string method; ///< filter type ("" for the noisy input)
    std::map<std::string, std::string> params; ///< explicit parameters of this setting
    std::vector<FrameResult> frames;
    double medianMs = 0.0, meanMs = 0.0, minMs = 0.0;
    double medianCpuMs = 0.0; ///< median process CPU time per frame (robust on a shared machine)
    std::map<std::string, double> means; ///< sequenceMeans(frames)
};

/// "svgf/iterations=2/alpha=0.1" -> method "svgf" and its parameters (label = the text; the
/// --benchmark:methods= items, with and without :size=).
MethodResult parseSetting(const std::string& item);

/// Crops of one frame, as PNG file names relative to the report folder.
struct CropSet {
    int frame = -1;
    int x = 0, y = 0, width = 0, height = 0; ///< crop rectangle in the frame
    std::vector<std::pair<std::string, std::string>> images; ///< (label, file name)
};

/// Everything the report files show.
struct BenchmarkReport {
    std::string commandLine;
    std::string input, reference;
    int width = 0, height = 0, frameCount = 0, repeat = 1;
    int threads = 0; ///< --threads (0 = all cores)
    double ioMsPerFrame = 0.0; ///< file reading per frame (input + reference), milliseconds
    unsigned hardwareThreads = 0;
    std::string errorMetric = "rmse"; ///< y axis of the plot
    MethodResult noisy; ///< the input itself (no timing); empty label = not scored
    std::vector<MethodResult> methods;
    std::vector<CropSet> crops;
    std::vector<std::string> warnings;
};

/// Median of a list of times (0 for an empty list).
double median(std::vector<double> values);
/// Text with <, >, & and " escaped for HTML and SVG.
std::string escapeXml(const std::string& s);
/// CPU time of this process so far (every thread), milliseconds.
double processCpuMs();

/// Indices of methods on the Pareto front of (medianMs, error): no other method is at least as
/// fast and at least as good with one of the two strictly better. NaN errors are never on it.
std::vector<bool> paretoFront(const std::vector<MethodResult>& methods, const MetricColumn& error);

/// Write DIR/results.json (everything, per frame) and DIR/results.csv (one row per method and
/// frame, plus a "mean" row per method). Atomic writes; throws CliError naming the file.
void writeResultsJson(const std::string& dir, const BenchmarkReport& report);
void writeResultsCsv(const std::string& dir, const BenchmarkReport& report);
/// The run-time-vs-error plot as a standalone SVG string (hand-written, no dependencies).
std::string runtimeErrorSvg(const BenchmarkReport& report);
/// DIR/index.html: tables, the plot, the crops.
void writeIndexHtml(const std::string& dir, const BenchmarkReport& report);
/// Write text to a file atomically (temporary file + rename); throws CliError.
void writeTextAtomic(const std::string& path, const std::string& text);

} // namespace afntool
