// SPDX-License-Identifier: Apache-2.0
// index.html of a benchmark report: summary table, the run-time-vs-error plot, side-by-side crops,
// per-frame tables. Static HTML with inline CSS; no scripts.
#include "report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace afntool {

namespace {

std::string fmt(double v, const char* f)
{
    if (std::isnan(v))
        return "NaN";
    if (std::isinf(v))
        return v > 0 ? "&infin;" : "-&infin;";
    char buf[48];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

const char* formatOf(const MetricColumn& c)
{
    const std::string n = c.name;
    if (n == "psnr" || n == "psnr8" || n == "tpsnr")
        return "%.2f";
    if (n == "tge")
        return "%.5f";
    return "%.4f";
}

const char* kStyle = R"(<style>
body { font-family: sans-serif; margin: 24px; color: #222; max-width: 1400px; }
table { border-collapse: collapse; margin: 8px 0 16px; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: right; }
th { background: #f2f2f2; } td.l, th.l { text-align: left; }
td.best { font-weight: bold; background: #e8f4e8; }
.crops { display: flex; flex-wrap: wrap; gap: 10px; }
figure { margin: 0; text-align: center; font-size: 12px; }
figure img { image-rendering: pixelated; border: 1px solid #888; }
code { background: #f4f4f4; padding: 1px 4px; } .note { color: #555; font-size: 13px; }
</style>)";

/// One table of methods (summary) with the best value per metric column highlighted.
void summaryTable(std::ostringstream& h, const BenchmarkReport& r)
{
    const MetricColumn& error = metricColumn(r.errorMetric);
    const std::vector<bool> front = paretoFront(r.methods, error);
    const std::vector<MetricColumn>& cols = metricColumns();
    std::vector<double> best(cols.size(), NAN);
    for (std::size_t c = 0; c < cols.size(); ++c) {
        int distinct = 0;
        for (const MethodResult& m : r.methods) {
            const double v = m.means.at(cols[c].name);
            if (std::isnan(v))
                continue;
            distinct += std::isnan(best[c]) || v != best[c];
            if (std::isnan(best[c]) || (cols[c].higherIsBetter ? v > best[c] : v < best[c]))
                best[c] = v;
        }
        if (distinct < 2)
            best[c] = NAN; // nothing to single out
    }
    h << "<table><tr><th class=l>method / setting</th><th>median ms/frame</th><th>mean ms</th>"
      << "<th>min ms</th><th>fps</th><th>median CPU ms</th>";
    for (const MetricColumn& c : cols)
        h << "<th>" << escapeXml(c.label) << "</th>";
    h << "<th>Pareto</th></tr>\n";
    auto row = [&](const MethodResult& m, bool timed, bool pareto) {
        h << "<tr><td class=l>" << escapeXml(m.label) << "</td>";
        if (timed)
            h << "<td>" << fmt(m.medianMs, "%.2f") << "</td><td>" << fmt(m.meanMs, "%.2f")
              << "</td><td>" << fmt(m.minMs, "%.2f") << "</td><td>"
              << fmt(m.medianMs > 0 ? 1000.0 / m.medianMs : NAN, "%.1f") << "</td><td>"
              << fmt(m.medianCpuMs, "%.2f") << "</td>";
        else
            h << "<td>-</td><td>-</td><td>-</td><td>-</td><td>-</td>";
        for (std::size_t c = 0; c < cols.size(); ++c) {
            const double v = m.means.at(cols[c].name);
            const bool isBest = timed && !std::isnan(v) && v == best[c];
            h << "<td" << (isBest ? " class=best" : "") << ">" << fmt(v, formatOf(cols[c]))
              << "</td>";
        }
        h << "<td>" << (timed ? (pareto ? "&#9679;" : "") : "-") << "</td></tr>\n";
    };
    if (!r.noisy.label.empty())
        row(r.noisy, false, false);
    for (std::size_t i = 0; i < r.methods.size(); ++i)
        row(r.methods[i], true, front[i]);
    h << "</table>\n";
}

void frameTable(std::ostringstream& h, const MethodResult& m, bool timed)
{
    h << "<details><summary>" << escapeXml(m.label)
      << ": per frame</summary><table><tr><th>frame</th>";
    if (timed)
        h << "<th>ms</th><th>CPU ms</th>";
    for (const MetricColumn& c : metricColumns())
        h << "<th>" << escapeXml(c.label) << "</th>";
    h << "</tr>\n";
    for (const FrameResult& f : m.frames) {
        h << "<tr><td>" << f.frame << "</td>";
        if (timed)
            h << "<td>" << fmt(f.ms, "%.2f") << "</td><td>" << fmt(f.cpuMs, "%.2f") << "</td>";
        for (const MetricColumn& c : metricColumns())
            h << "<td>" << (c.temporal && !f.hasTemporal ? "-" : fmt(c.get(f), formatOf(c)))
              << "</td>";
        h << "</tr>\n";
    }
    h << "</table></details>\n";
}

} // namespace

void writeIndexHtml(const std::string& dir, const BenchmarkReport& r)
{
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      << "<title>afn benchmark: run time against error</title>\n"
      << kStyle << "</head><body>\n"
      << "<h1>Run time against error</h1>\n<p>Input <code>" << escapeXml(r.input)
      << "</code>, references <code>" << escapeXml(r.reference) << "</code>: " << r.width
      << "&times;" << r.height << ", " << r.frameCount << " frame(s), each method run " << r.repeat
      << " time(s) over the sequence; threads: "
      << (r.threads > 0 ? std::to_string(r.threads) : "all") << " (" << r.hardwareThreads
      << " hardware threads). File I/O " << fmt(r.ioMsPerFrame, "%.1f")
      << " ms per frame (input + reference), not included in the times.</p>\n"
      << "<p class=note>Command: <code>" << escapeXml(r.commandLine) << "</code></p>\n";
    for (const std::string& w : r.warnings)
        h << "<p class=note>Warning: " << escapeXml(w) << "</p>\n";

    h << "<h2>Summary</h2>\n";
    summaryTable(h, r);
    h << "<p class=note>Times: median (mean, min) wall time of the denoise stage per frame "
         "(binding "
         "inputs, execute, fetching the output), every frame of every run; CPU ms: process CPU "
         "time "
         "of all threads over the same stage (less sensitive to other load on a shared machine). "
         "Metrics: mean of per-frame values; "
         "PSNR, SSIM and RMSE on T(x) = clip(max(x,0)<sup>1/2.2</sup>, 0, 1); SMAPE on linear "
         "values "
         "with &epsilon; = 0.001 (AFN Eq. 5); 8-bit variants quantise T(x) to 8 bits; the temporal "
         "gradient error is mean |(o<sub>t</sub>&minus;o<sub>t&minus;1</sub>) &minus; "
         "(r<sub>t</sub>&minus;r<sub>t&minus;1</sub>)| on T(x) over frames 2..N. Best per column "
         "in "
         "bold. Definitions: <code>docs/metrics.md</code>.</p>\n";

    h << "<h2>Run time against error</h2>\n<p><img src=\"runtime-vs-error.svg\" alt=\"run time "
         "against "
      << escapeXml(metricColumn(r.errorMetric).label) << "\"></p>\n";

    for (const CropSet& c : r.crops) {
        h << "<h2>Frame " << c.frame << ": crop " << c.width << "&times;" << c.height << " at ("
          << c.x << ", " << c.y << ")</h2>\n<div class=crops>\n";
        for (const auto& [label, file] : c.images)
            h << "<figure><img src=\"" << escapeXml(file) << "\" width=\"" << 2 * c.width
              << "\" height=\"" << 2 * c.height << "\" alt=\"" << escapeXml(label)
              << "\"><figcaption>" << escapeXml(label) << "</figcaption></figure>\n";
        h << "</div>\n<p class=note>Display transform of the colour config's default view; shown "
             "at 2&times; (nearest neighbour).</p>\n";
    }

    h << "<h2>Per frame</h2>\n";
    if (!r.noisy.label.empty())
        frameTable(h, r.noisy, false);
    for (const MethodResult& m : r.methods)
        frameTable(h, m, true);
    h << "<p class=note>Data: <a href=\"results.json\">results.json</a>, "
         "<a href=\"results.csv\">results.csv</a>.</p>\n</body></html>\n";
    writeTextAtomic(dir + "/index.html", h.str());
}

} // namespace afntool
