// SPDX-License-Identifier: Apache-2.0
// Metric columns, sequence means, the Pareto front, and results.json / results.csv.
#include "report.h"

#include "cli_error.h"
#include "json_writer.h"

#include "afn/afn.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include <time.h>
#include <unistd.h>

namespace afntool {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

} // namespace

const std::vector<MetricColumn>& metricColumns()
{
    // clang-format off
    static const std::vector<MetricColumn> columns = {
        { "psnr", "PSNR (dB)", true, false, [](const FrameResult& f) { return f.metrics.psnr; } },
        { "ssim", "SSIM", true, false, [](const FrameResult& f) { return f.metrics.ssim; } },
        { "rmse", "RMSE", false, false, [](const FrameResult& f) { return f.metrics.rmse; } },
        { "smape", "SMAPE", false, false, [](const FrameResult& f) { return f.metrics.smape; } },
        { "rmseLinear", "RMSE linear", false, false, [](const FrameResult& f) { return f.metrics.rmseLinear; } },
        { "smapeTonemapped", "SMAPE T(x)", false, false, [](const FrameResult& f) { return f.metrics.smapeTonemapped; } },
        { "psnr8", "PSNR 8-bit", true, false, [](const FrameResult& f) { return f.metrics.psnr8; } },
        { "ssim8", "SSIM 8-bit", true, false, [](const FrameResult& f) { return f.metrics.ssim8; } },
        { "rmse8", "RMSE 8-bit", false, false, [](const FrameResult& f) { return f.metrics.rmse8; } },
        { "tge", "temporal grad. err.", false, true, [](const FrameResult& f) { return f.temporal.gradientError; } },
        { "tpsnr", "temporal PSNR (dB)", true, true, [](const FrameResult& f) { return f.temporal.gradientPsnr; } },
    };
    // clang-format on
    return columns;
}

const MetricColumn& metricColumn(const std::string& name)
{
    std::string names;
    for (const MetricColumn& c : metricColumns()) {
        if (name == c.name)
            return c;
        names += names.empty() ? c.name : std::string(", ") + c.name;
    }
    throw CliError("unknown metric '" + name + "' (known: " + names + ")");
}

std::map<std::string, double> sequenceMeans(const std::vector<FrameResult>& frames)
{
    std::map<std::string, double> out;
    for (const MetricColumn& c : metricColumns()) {
        double sum = 0.0;
        int n = 0;
        for (const FrameResult& f : frames) {
            if (c.temporal && !f.hasTemporal)
                continue;
            sum += c.get(f); // NaN and inf propagate on purpose
            ++n;
        }
        out[c.name] = n > 0 ? sum / n : kNaN;
    }
    return out;
}

double median(std::vector<double> values)
{
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string escapeXml(const std::string& s)
{
    std::string o;
    for (char c : s) {
        switch (c) {
        case '<':
            o += "&lt;";
            break;
        case '>':
            o += "&gt;";
            break;
        case '&':
            o += "&amp;";
            break;
        case '"':
            o += "&quot;";
            break;
        default:
            o += c;
        }
    }
    return o;
}

double processCpuMs()
{
    timespec ts {};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

std::vector<bool> paretoFront(const std::vector<MethodResult>& methods, const MetricColumn& error)
{
    auto err = [&](const MethodResult& m) {
        const double v = m.means.at(error.name);
        return error.higherIsBetter ? -v : v; // lower is better from here on
    };
    std::vector<bool> front(methods.size(), false);
    for (std::size_t i = 0; i < methods.size(); ++i) {
        const double ei = err(methods[i]), ti = methods[i].medianMs;
        if (std::isnan(ei))
            continue;
        bool dominated = false;
        for (std::size_t j = 0; j < methods.size() && !dominated; ++j) {
            const double ej = err(methods[j]), tj = methods[j].medianMs;
            if (j == i || std::isnan(ej))
                continue;
            dominated = tj <= ti && ej <= ei && (tj < ti || ej < ei);
        }
        front[i] = !dominated;
    }
    return front;
}

void writeTextAtomic(const std::string& path, const std::string& text)
{
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        f.flush();
        if (!f) {
            std::remove(tmp.c_str());
            throw CliError("cannot write file", path);
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw CliError("cannot write file (rename failed)", path);
    }
}

namespace {

void writeMethodJson(JsonWriter& j, const MethodResult& m, bool pareto)
{
    j.beginObject();
    j.field("label", m.label).field("method", m.method);
    j.key("params").beginObject();
    for (const auto& [k, v] : m.params)
        j.field(k, v);
    j.endObject();
    j.field("medianMs", m.medianMs).field("meanMs", m.meanMs).field("minMs", m.minMs);
    j.field("medianCpuMs", m.medianCpuMs);
    j.field("pareto", pareto);
    j.key("mean").beginObject();
    for (const auto& [k, v] : m.means)
        j.field(k, v);
    j.endObject();
    j.key("frames").beginArray();
    for (const FrameResult& f : m.frames) {
        j.beginObject().field("frame", f.frame).field("ms", f.ms).field("cpuMs", f.cpuMs);
        for (const MetricColumn& c : metricColumns()) {
            if (c.temporal && !f.hasTemporal)
                continue;
            j.field(c.name, c.get(f));
        }
        j.field("nonFiniteTest", static_cast<long long>(f.metrics.nonFiniteTest));
        j.field("nonFiniteReference", static_cast<long long>(f.metrics.nonFiniteReference));
        j.endObject();
    }
    j.endArray();
    j.endObject();
}

std::string csvNumber(double v)
{
    if (std::isnan(v))
        return "nan";
    if (std::isinf(v))
        return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string csvText(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string o = "\"";
    for (char c : s)
        o += c == '"' ? std::string("\"\"") : std::string(1, c);
    return o + "\"";
}

} // namespace

void writeResultsJson(const std::string& dir, const BenchmarkReport& r)
{
    const MetricColumn& error = metricColumn(r.errorMetric);
    const std::vector<bool> front = paretoFront(r.methods, error);
    JsonWriter j;
    j.beginObject();
    j.field("tool", "afntool --benchmark");
    j.field("version",
        std::to_string(AFN_VERSION_MAJOR) + "." + std::to_string(AFN_VERSION_MINOR) + "."
            + std::to_string(AFN_VERSION_PATCH));
    j.field("command", r.commandLine).field("input", r.input).field("reference", r.reference);
    j.field("width", r.width).field("height", r.height).field("frames", r.frameCount);
    j.field("repeat", r.repeat).field("threads", r.threads);
    j.field("hardwareThreads", static_cast<long long>(r.hardwareThreads));
    j.field("errorMetric", r.errorMetric);
    j.field("conventions",
        "docs/metrics.md: T(x)=clip(max(x,0)^(1/2.2),0,1); PSNR/SSIM/RMSE on "
        "T(x); SMAPE linear eps=1e-3; sequence value = mean of per-frame values; "
        "non-finite JSON numbers (PSNR of identical images, NaN) are null; "
        "ms = median denoise-stage time per frame, file I/O excluded");
    j.key("noisy");
    if (r.noisy.label.empty())
        j.value("not scored");
    else
        writeMethodJson(j, r.noisy, false);
    j.key("methods").beginArray();
    for (std::size_t i = 0; i < r.methods.size(); ++i)
        writeMethodJson(j, r.methods[i], front[i]);
    j.endArray();
    j.key("crops").beginArray();
    for (const CropSet& c : r.crops) {
        j.beginObject().field("frame", c.frame).field("x", c.x).field("y", c.y);
        j.field("width", c.width).field("height", c.height);
        j.key("images").beginArray();
        for (const auto& [label, file] : c.images)
            j.beginObject().field("label", label).field("file", file).endObject();
        j.endArray().endObject();
    }
    j.endArray();
    j.field("warnings", r.warnings);
    j.endObject();
    writeTextAtomic(dir + "/results.json", j.str() + "\n");
}

void writeResultsCsv(const std::string& dir, const BenchmarkReport& r)
{
    std::ostringstream os;
    os << "label,method,frame,ms,cpuMs";
    for (const MetricColumn& c : metricColumns())
        os << "," << c.name;
    os << "\n";
    auto rows = [&](const MethodResult& m) {
        for (const FrameResult& f : m.frames) {
            os << csvText(m.label) << "," << m.method << "," << f.frame << "," << csvNumber(f.ms)
               << "," << csvNumber(f.cpuMs);
            for (const MetricColumn& c : metricColumns())
                os << "," << (c.temporal && !f.hasTemporal ? "" : csvNumber(c.get(f)));
            os << "\n";
        }
        os << csvText(m.label) << "," << m.method << ",mean," << csvNumber(m.medianMs) << ","
           << csvNumber(m.medianCpuMs);
        for (const MetricColumn& c : metricColumns())
            os << "," << csvNumber(m.means.at(c.name));
        os << "\n";
    };
    if (!r.noisy.label.empty())
        rows(r.noisy);
    for (const MethodResult& m : r.methods)
        rows(m);
    writeTextAtomic(dir + "/results.csv", os.str());
}

} // namespace afntool
