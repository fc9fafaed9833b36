// SPDX-License-Identifier: Apache-2.0
// runtime-vs-error.svg: median ms per frame (x) against the sequence mean of one error metric (y),
// one point per method and setting, the Pareto front marked and joined. Hand-written SVG 1.1.
#include "report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace afntool {

namespace {

std::string num(double v, const char* fmt = "%.1f")
{
    char buf[48];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

/// Round step for about `n` ticks over `range` (1, 2 or 5 times a power of ten).
double niceStep(double range, int n)
{
    if (!(range > 0.0))
        return 1.0;
    const double raw = range / n;
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : { 1.0, 2.0, 5.0, 10.0 })
        if (raw <= m * p)
            return m * p;
    return 10.0 * p;
}

/// Printf format with enough decimals for a tick step.
std::string tickFormat(double step)
{
    const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    return "%." + std::to_string(std::min(decimals, 6)) + "f";
}

} // namespace

std::string runtimeErrorSvg(const BenchmarkReport& r)
{
    const MetricColumn& metric = metricColumn(r.errorMetric);
    const std::vector<bool> front = paretoFront(r.methods, metric);
    const double W = 820, H = 460, left = 80, right = 250, top = 40, bottom = 60;
    const double pw = W - left - right, ph = H - top - bottom;

    // Axis ranges from the finite points (and the noisy input's error line).
    double tMax = 0.0, eMin = INFINITY, eMax = -INFINITY;
    for (const MethodResult& m : r.methods) {
        const double e = m.means.at(metric.name);
        if (!std::isfinite(e))
            continue;
        tMax = std::max(tMax, m.medianMs);
        eMin = std::min(eMin, e);
        eMax = std::max(eMax, e);
    }
    const double noisyErr = r.noisy.label.empty() ? NAN : r.noisy.means.at(metric.name);
    if (std::isfinite(noisyErr))
        eMin = std::min(eMin, noisyErr), eMax = std::max(eMax, noisyErr);
    if (!std::isfinite(eMin))
        eMin = 0.0, eMax = 1.0;
    if (eMax - eMin < 1e-9)
        eMin -= 0.5 * std::max(1e-3, std::abs(eMin)), eMax += 0.5 * std::max(1e-3, std::abs(eMax));
    const double ePad = 0.08 * (eMax - eMin);
    eMin -= ePad, eMax += ePad;
    const double xStep = niceStep(tMax > 0 ? tMax * 1.1 : 1.0, 6);
    const double xMax = xStep * std::ceil((tMax > 0 ? tMax * 1.1 : 1.0) / xStep);
    const double yStep = niceStep(eMax - eMin, 6);
    const double yLo = yStep * std::floor(eMin / yStep), yHi = yStep * std::ceil(eMax / yStep);
    auto X = [&](double t) { return left + pw * t / xMax; };
    auto Y = [&](double e) { return top + ph * (1.0 - (e - yLo) / (yHi - yLo)); };

    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" viewBox=\"0 0 " << W << " " << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left << "\" y=\"22\" font-size=\"15\">Run time against error (" << r.width
      << "x" << r.height << ", " << r.frameCount << " frames)</text>\n";
    // Grid and ticks.
    const std::string xf = tickFormat(xStep), yf = tickFormat(yStep);
    for (double t = 0.0; t <= xMax + 1e-9 * xMax; t += xStep)
        s << "<line x1=\"" << num(X(t)) << "\" y1=\"" << top << "\" x2=\"" << num(X(t))
          << "\" y2=\"" << top + ph << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << num(X(t))
          << "\" y=\"" << top + ph + 16 << "\" text-anchor=\"middle\">" << num(t, xf.c_str())
          << "</text>\n";
    for (double e = yLo; e <= yHi + 1e-9 * std::abs(yHi) + 1e-12; e += yStep)
        s << "<line x1=\"" << left << "\" y1=\"" << num(Y(e)) << "\" x2=\"" << left + pw
          << "\" y2=\"" << num(Y(e)) << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << left - 6
          << "\" y=\"" << num(Y(e) + 4) << "\" text-anchor=\"end\">" << num(e, yf.c_str())
          << "</text>\n";
    s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#444\"/>\n"
      << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 18
      << "\" text-anchor=\"middle\">median denoise time per frame (ms)</text>\n"
      << "<text transform=\"translate(18," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << escapeXml(metric.label)
      << (metric.higherIsBetter ? " (higher is better)" : " (lower is better)") << "</text>\n";
    if (std::isfinite(noisyErr))
        s << "<line x1=\"" << left << "\" y1=\"" << num(Y(noisyErr)) << "\" x2=\"" << left + pw
          << "\" y2=\"" << num(Y(noisyErr))
          << "\" stroke=\"#999\" stroke-dasharray=\"5,4\"/>\n<text x=\"" << left + pw - 4
          << "\" y=\"" << num(Y(noisyErr) - 5)
          << "\" text-anchor=\"end\" fill=\"#777\">noisy input</text>\n";

    // Pareto front: its points joined in time order.
    std::vector<std::pair<double, double>> fp;
    for (std::size_t i = 0; i < r.methods.size(); ++i)
        if (front[i])
            fp.emplace_back(r.methods[i].medianMs, r.methods[i].means.at(metric.name));
    std::sort(fp.begin(), fp.end());
    if (fp.size() > 1) {
        s << "<polyline fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" points=\"";
        for (const auto& [t, e] : fp)
            s << num(X(t)) << "," << num(Y(e)) << " ";
        s << "\"/>\n";
    }
    // Points and labels; the legend lists the methods with their numbers.
    double ly = top + 14;
    int skipped = 0;
    for (std::size_t i = 0; i < r.methods.size(); ++i) {
        const MethodResult& m = r.methods[i];
        const double e = m.means.at(metric.name);
        const std::string label = escapeXml(m.label);
        if (!std::isfinite(e)) {
            ++skipped;
            continue;
        }
        const char* colour = front[i] ? "#d62728" : "#1f77b4";
        s << "<circle cx=\"" << num(X(m.medianMs)) << "\" cy=\"" << num(Y(e))
          << "\" r=\"5\" fill=\"" << colour << "\"><title>" << label << ": "
          << num(m.medianMs, "%.2f") << " ms, " << num(e, "%.5g") << "</title></circle>\n<text x=\""
          << num(X(m.medianMs) + 8) << "\" y=\"" << num(Y(e) - 6) << "\" fill=\"" << colour << "\">"
          << label << "</text>\n";
        s << "<text x=\"" << left + pw + 14 << "\" y=\"" << ly << "\" font-size=\"11\" fill=\""
          << colour << "\">" << label << ": " << num(m.medianMs, "%.2f") << " ms, "
          << num(e, "%.4g") << "</text>\n";
        ly += 16;
    }
    s << "<circle cx=\"" << left + pw + 18 << "\" cy=\"" << ly + 6
      << "\" r=\"5\" fill=\"#d62728\"/>"
      << "<text x=\"" << left + pw + 28 << "\" y=\"" << ly + 10 << "\">Pareto front</text>\n"
      << "<circle cx=\"" << left + pw + 18 << "\" cy=\"" << ly + 24
      << "\" r=\"5\" fill=\"#1f77b4\"/>"
      << "<text x=\"" << left + pw + 28 << "\" y=\"" << ly + 28 << "\">dominated</text>\n";
    if (skipped)
        s << "<text x=\"" << left + pw + 14 << "\" y=\"" << ly + 50 << "\" fill=\"#b00\">"
          << skipped << " method(s) with NaN error not drawn</text>\n";
    s << "</svg>\n";
    return s.str();
}

} // namespace afntool
