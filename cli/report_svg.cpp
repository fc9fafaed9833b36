// SPDX-License-Identifier: Apache-2.0
// runtime-vs-error.svg: one panel per metric (the report's error metric, SSIM, the temporal
// gradient error), each the median ms per frame (x, shared by the panels) against the sequence
// mean of the metric (y, fitted to the methods' values), the Pareto front of that metric marked
// and joined. Points are numbered; the legend under the panels names them. Hand-written SVG 1.1.
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

// Text boxes are estimated with a width of kCharWidth * font size per character: an upper bound
// of the mean advance of sans-serif fonts (DejaVu Sans digits: 0.64 em), so boxes that do not
// overlap here do not overlap on screen. tests/integration/test_afntool_report.cpp uses the same.
constexpr double kCharWidth = 0.65, kLabelSize = 12.0;

struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
    bool inside(const Box& o) const { return x0 >= o.x0 && x1 <= o.x1 && y0 >= o.y0 && y1 <= o.y1; }
};

/// Box of a label drawn with text-anchor start at baseline (x, y).
Box labelBox(double x, double y, const std::string& text)
{
    return { x, y - kLabelSize * 0.8, x + kCharWidth * kLabelSize * text.size(),
        y + kLabelSize * 0.25 };
}

/// The metrics with a panel: the report's error metric, SSIM and the temporal gradient error.
std::vector<const MetricColumn*> panelMetrics(const BenchmarkReport& r)
{
    std::vector<const MetricColumn*> out;
    for (const std::string& name : { r.errorMetric, std::string("ssim"), std::string("tge") }) {
        const MetricColumn& c = metricColumn(name);
        if (std::find(out.begin(), out.end(), &c) == out.end())
            out.push_back(&c);
    }
    return out;
}

struct Frame {
    double x, y, w, h; ///< plot area of a panel
    double xMax, xStep; ///< shared time axis
};

void drawPanel(
    std::ostringstream& s, const BenchmarkReport& r, const MetricColumn& metric, const Frame& f)
{
    const std::vector<bool> front = paretoFront(r.methods, metric);
    // The y axis is fitted to the methods' finite values only: the noisy input, usually far off,
    // is marked at the panel's edge instead of stretching the axis.
    double lo = INFINITY, hi = -INFINITY;
    for (const MethodResult& m : r.methods) {
        const double v = m.means.at(metric.name);
        if (std::isfinite(v))
            lo = std::min(lo, v), hi = std::max(hi, v);
    }
    const bool any = std::isfinite(lo);
    if (!any)
        lo = 0.0, hi = 1.0;
    if (hi - lo < 1e-9)
        lo -= 0.5 * std::max(1e-3, std::abs(lo)), hi += 0.5 * std::max(1e-3, std::abs(hi));
    const double pad = 0.08 * (hi - lo), step = niceStep(hi - lo + 2 * pad, 5);
    const double yLo = step * std::floor((lo - pad) / step),
                 yHi = step * std::ceil((hi + pad) / step);
    auto X = [&](double t) { return f.x + f.w * t / f.xMax; };
    auto Y = [&](double v) { return f.y + f.h * (1.0 - (v - yLo) / (yHi - yLo)); };

    s << "<g class=\"panel\" data-metric=\"" << metric.name << "\" data-y-lo=\"" << num(yLo, "%.9g")
      << "\" data-y-hi=\"" << num(yHi, "%.9g") << "\">\n<text x=\"" << f.x << "\" y=\"" << f.y - 10
      << "\" font-size=\"14\" font-weight=\"bold\">" << escapeXml(metric.label)
      << (metric.higherIsBetter ? " (higher is better)" : " (lower is better)") << "</text>\n";
    const std::string xf = tickFormat(f.xStep), yf = tickFormat(step);
    for (double t = 0.0; t <= f.xMax * (1 + 1e-9); t += f.xStep)
        s << "<line x1=\"" << num(X(t)) << "\" y1=\"" << f.y << "\" x2=\"" << num(X(t))
          << "\" y2=\"" << f.y + f.h << "\" stroke=\"#e4e4e4\"/><text x=\"" << num(X(t))
          << "\" y=\"" << f.y + f.h + 16 << "\" text-anchor=\"middle\">" << num(t, xf.c_str())
          << "</text>\n";
    for (double v = yLo; v <= yHi + 1e-9 * (yHi - yLo); v += step)
        s << "<line x1=\"" << f.x << "\" y1=\"" << num(Y(v)) << "\" x2=\"" << f.x + f.w
          << "\" y2=\"" << num(Y(v)) << "\" stroke=\"#e4e4e4\"/><text x=\"" << f.x - 6 << "\" y=\""
          << num(Y(v) + 4) << "\" text-anchor=\"end\">" << num(v, yf.c_str()) << "</text>\n";
    s << "<rect x=\"" << f.x << "\" y=\"" << f.y << "\" width=\"" << f.w << "\" height=\"" << f.h
      << "\" fill=\"none\" stroke=\"#444\"/>\n<text x=\"" << f.x + f.w / 2 << "\" y=\""
      << f.y + f.h + 34 << "\" text-anchor=\"middle\">median denoise time per frame (ms)</text>\n";

    // Obstacles for the labels: every point; labels must stay inside the plot area.
    const Box area { f.x + 2, f.y + 2, f.x + f.w - 2, f.y + f.h - 2 };
    std::vector<Box> taken;
    for (const MethodResult& m : r.methods) {
        const double v = m.means.at(metric.name);
        if (std::isfinite(v))
            taken.push_back({ X(m.medianMs) - 6, Y(v) - 6, X(m.medianMs) + 6, Y(v) + 6 });
    }
    auto place
        = [&](double px, double py, const std::string& text, Box& out, double& tx, double& ty) {
              const double w = kCharWidth * kLabelSize * text.size();
              const double cand[][2] = { { px + 9, py + 4 }, { px - 9 - w, py + 4 },
                  { px - w / 2, py - 10 }, { px - w / 2, py + 19 }, { px + 9, py - 9 },
                  { px + 9, py + 17 }, { px - 9 - w, py - 9 }, { px - 9 - w, py + 17 } };
              for (const auto& c : cand) {
                  const Box b = labelBox(c[0], c[1], text);
                  if (!b.inside(area) || std::any_of(taken.begin(), taken.end(), [&](const Box& o) {
                          return b.overlaps(o);
                      }))
                      continue;
                  out = b, tx = c[0], ty = c[1];
                  return true;
              }
              return false;
          };

    std::vector<std::pair<double, double>> fp;
    for (std::size_t i = 0; i < r.methods.size(); ++i)
        if (front[i])
            fp.emplace_back(r.methods[i].medianMs, r.methods[i].means.at(metric.name));
    std::sort(fp.begin(), fp.end());
    if (fp.size() > 1) {
        s << "<polyline fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" points=\"";
        for (const auto& [t, v] : fp)
            s << num(X(t)) << "," << num(Y(v)) << " ";
        s << "\"/>\n";
        // The front's segments are obstacles too: small boxes every 3 pixels along them.
        for (std::size_t k = 1; k < fp.size(); ++k) {
            const double ax = X(fp[k - 1].first), ay = Y(fp[k - 1].second);
            const double bx = X(fp[k].first), by = Y(fp[k].second);
            const int n = 1 + static_cast<int>(std::hypot(bx - ax, by - ay) / 3.0);
            for (int j = 0; j <= n; ++j) {
                const double x = ax + (bx - ax) * j / n, y = ay + (by - ay) * j / n;
                taken.push_back({ x - 1.5, y - 1.5, x + 1.5, y + 1.5 });
            }
        }
    }
    const double noisy = r.noisy.label.empty() ? NAN : r.noisy.means.at(metric.name);
    if (std::isfinite(noisy)) {
        if (noisy >= yLo && noisy <= yHi) {
            s << "<line x1=\"" << f.x << "\" y1=\"" << num(Y(noisy)) << "\" x2=\"" << f.x + f.w
              << "\" y2=\"" << num(Y(noisy)) << "\" stroke=\"#999\" stroke-dasharray=\"5,4\"/>\n";
            Box b;
            double tx, ty;
            const std::string text = "noisy input";
            if (place(f.x + f.w - 8 - kCharWidth * kLabelSize * text.size() - 9, Y(noisy), text, b,
                    tx, ty)) {
                taken.push_back(b);
                s << "<text class=\"point-label\" x=\"" << num(tx) << "\" y=\"" << num(ty)
                  << "\" fill=\"#777\">" << text << "</text>\n";
            }
        } else {
            // Off the axis: a note at the edge it lies beyond (left or right, clear of points).
            const bool above = noisy > yHi;
            const std::string text = std::string("noisy input ") + num(noisy, "%.4g")
                + (above ? " (above)" : " (below)");
            const double ty = above ? f.y + 16 : f.y + f.h - 8;
            const double tw = kCharWidth * kLabelSize * text.size();
            for (const double tx : { f.x + 8, f.x + f.w - 8 - tw }) {
                const Box b = labelBox(tx, ty, text);
                if (!b.inside(area) || std::any_of(taken.begin(), taken.end(), [&](const Box& o) {
                        return b.overlaps(o);
                    }))
                    continue;
                taken.push_back(b);
                s << "<text class=\"point-label\" x=\"" << num(tx) << "\" y=\"" << num(ty)
                  << "\" fill=\"#777\">" << escapeXml(text) << "</text>\n";
                break;
            }
        }
    }

    int skipped = 0;
    for (std::size_t i = 0; i < r.methods.size(); ++i) {
        const MethodResult& m = r.methods[i];
        const double v = m.means.at(metric.name);
        if (!std::isfinite(v)) {
            ++skipped;
            continue;
        }
        const char* colour = front[i] ? "#d62728" : "#1f77b4";
        s << "<circle cx=\"" << num(X(m.medianMs)) << "\" cy=\"" << num(Y(v))
          << "\" r=\"5\" fill=\"" << colour << "\"><title>" << escapeXml(m.label) << ": "
          << num(m.medianMs, "%.2f") << " ms, " << num(v, "%.5g") << "</title></circle>\n";
        // The number of the legend entry; where it cannot be placed clear of everything else,
        // the point stays unlabelled (its tooltip and the legend still name it).
        Box b;
        double tx, ty;
        const std::string text = std::to_string(i + 1);
        if (place(X(m.medianMs), Y(v), text, b, tx, ty)) {
            taken.push_back(b);
            s << "<text class=\"point-label\" x=\"" << num(tx) << "\" y=\"" << num(ty)
              << "\" fill=\"" << colour << "\">" << text << "</text>\n";
        }
    }
    if (skipped)
        s << "<text x=\"" << f.x + 8 << "\" y=\"" << f.y + f.h - 24 << "\" fill=\"#b00\">"
          << skipped << " method(s) with NaN not drawn</text>\n";
    if (!any)
        s << "<text x=\"" << f.x + f.w / 2 << "\" y=\"" << f.y + f.h / 2
          << "\" text-anchor=\"middle\" fill=\"#777\">no values"
          << (metric.temporal ? " (one frame: no temporal metric)" : "") << "</text>\n";
    s << "</g>\n";
}

} // namespace

std::string runtimeErrorSvg(const BenchmarkReport& r)
{
    const std::vector<const MetricColumn*> metrics = panelMetrics(r);
    const double panelW = 330, plotH = 250, left = 62, gapX = 72, top = 62;
    // Legend: a table under the panels, one row per method: number, name, median ms and the
    // panels' values, in columns placed after the longest name.
    const double legendTop = top + plotH + 76, rowH = 18;
    const double H = legendTop + rowH * (r.methods.size() + 1) + 6;
    std::size_t longest = 6;
    for (const MethodResult& m : r.methods)
        longest = std::max(longest, m.label.size());
    const double valuesX = left + 28 + kCharWidth * kLabelSize * longest + 16, valueW = 150;
    const double W = std::max(
        left + metrics.size() * (panelW + gapX), valuesX + (metrics.size() + 1) * valueW);

    double tMax = 0.0;
    for (const MethodResult& m : r.methods)
        tMax = std::max(tMax, std::isfinite(m.medianMs) ? m.medianMs : 0.0);
    const double span = tMax > 0 ? tMax * 1.1 : 1.0, xStep = niceStep(span, 4);
    const double xMax = xStep * std::ceil(span / xStep);

    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" viewBox=\"0 0 " << W << " " << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"" << left
      << "\" y=\"24\" font-size=\"16\">Run time against quality (" << r.width << "x" << r.height
      << ", " << r.frameCount << " frames); red: Pareto front of each metric</text>\n";
    for (std::size_t p = 0; p < metrics.size(); ++p)
        drawPanel(
            s, r, *metrics[p], { left + p * (panelW + gapX), top, panelW, plotH, xMax, xStep });

    s << "<g class=\"legend\">\n<text x=\"" << left + 28 << "\" y=\"" << legendTop
      << "\" font-weight=\"bold\">method / setting</text><text x=\"" << valuesX << "\" y=\""
      << legendTop << "\" font-weight=\"bold\">median ms</text>\n";
    for (std::size_t p = 0; p < metrics.size(); ++p)
        s << "<text x=\"" << valuesX + (p + 1) * valueW << "\" y=\"" << legendTop
          << "\" font-weight=\"bold\">" << escapeXml(metrics[p]->label) << "</text>\n";
    for (std::size_t i = 0; i < r.methods.size(); ++i) {
        const MethodResult& m = r.methods[i];
        const double y = legendTop + rowH * (i + 1);
        s << "<text x=\"" << left << "\" y=\"" << y << "\">" << i + 1 << "</text><text x=\""
          << left + 28 << "\" y=\"" << y << "\">" << escapeXml(m.label) << "</text><text x=\""
          << valuesX << "\" y=\"" << y << "\">" << num(m.medianMs, "%.1f") << "</text>\n";
        for (std::size_t p = 0; p < metrics.size(); ++p)
            s << "<text x=\"" << valuesX + (p + 1) * valueW << "\" y=\"" << y << "\">"
              << num(m.means.at(metrics[p]->name), "%.4g") << "</text>\n";
    }
    s << "</g>\n</svg>\n";
    return s.str();
}

} // namespace afntool
