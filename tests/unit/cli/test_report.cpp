// SPDX-License-Identifier: Apache-2.0
// afntool's report helpers: median, sequence means (NaN kept, temporal frames only), Pareto front,
// metric lookup, and the SVG plot's structure.
#include "report.h"

#include "cli_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace {

using namespace afntool;

MethodResult method(const std::string& label, double ms, double rmse)
{
    MethodResult m;
    m.label = m.method = label;
    for (int f = 0; f < 2; ++f) {
        FrameResult r;
        r.frame = f;
        r.metrics.rmse = rmse;
        r.metrics.psnr = -20.0 * std::log10(rmse);
        r.hasTemporal = f > 0;
        r.temporal.gradientError = 0.5 * rmse;
        m.frames.push_back(r);
    }
    m.medianMs = ms;
    m.means = sequenceMeans(m.frames);
    return m;
}

size_t count(const std::string& s, const std::string& what)
{
    size_t n = 0;
    for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1))
        ++n;
    return n;
}

TEST(Report, Median)
{
    EXPECT_EQ(median({}), 0.0);
    EXPECT_EQ(median({ 3.0, 1.0, 2.0 }), 2.0);
    EXPECT_EQ(median({ 4.0, 1.0, 3.0, 2.0 }), 2.5);
}

TEST(Report, SequenceMeansUseTemporalFramesOnlyAndKeepNaN)
{
    std::vector<FrameResult> frames(3);
    const double rmse[3] = { 0.1, 0.2, 0.6 };
    for (int i = 0; i < 3; ++i) {
        frames[i].metrics.rmse = rmse[i];
        frames[i].hasTemporal = i > 0;
        frames[i].temporal.gradientError = i == 0 ? 100.0 : 0.1 * i; // frame 0's value is unused
    }
    std::map<std::string, double> m = sequenceMeans(frames);
    EXPECT_NEAR(m.at("rmse"), 0.3, 1e-15);
    EXPECT_NEAR(m.at("tge"), 0.15, 1e-15);
    frames[1].metrics.rmse = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(std::isnan(sequenceMeans(frames).at("rmse")));
    EXPECT_TRUE(std::isnan(sequenceMeans({ frames[0] }).at("tge"))); // no temporal frame
}

TEST(Report, ParetoFront)
{
    // (ms, rmse): a (1, 0.3) b (5, 0.1) c (6, 0.2: dominated by b) d (5, 0.1: ties b) e NaN.
    std::vector<MethodResult> ms = { method("a", 1, 0.3), method("b", 5, 0.1), method("c", 6, 0.2),
        method("d", 5, 0.1), method("e", 0.5, std::nan("")) };
    const std::vector<bool> f = paretoFront(ms, metricColumn("rmse"));
    EXPECT_EQ(f, (std::vector<bool> { true, true, false, true, false }));
    // PSNR is higher-is-better: same front.
    EXPECT_EQ(paretoFront(ms, metricColumn("psnr")), f);
}

TEST(Report, UnknownMetricNamesTheKnownOnes)
{
    try {
        metricColumn("flip");
        FAIL() << "no error";
    } catch (const CliError& e) {
        EXPECT_NE(std::string(e.what()).find("smape"), std::string::npos);
    }
}

TEST(Report, SvgHasOnePointPerFiniteMethodAndTheFront)
{
    BenchmarkReport r;
    r.methods = { method("ta", 1, 0.3), method("svgf", 5, 0.1), method("bad", 2, std::nan("")) };
    const std::string svg = runtimeErrorSvg(r);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    // Panels: rmse, ssim, tge. "bad" has NaN rmse and tge (0.5 * rmse) but a finite SSIM (0).
    EXPECT_EQ(count(svg, "<g class=\"panel\""), 3u);
    EXPECT_EQ(count(svg, "<circle cx"), 2u + 3u + 2u);
    // Fronts: rmse and tge join ta and svgf; in SSIM (all 0) the fastest alone is on it.
    EXPECT_EQ(count(svg, "<polyline"), 2u);
    EXPECT_EQ(count(svg, "1 method(s) with NaN not drawn"), 2u);
    // The legend names every method once.
    EXPECT_EQ(count(svg, ">svgf</text>"), 1u);
}

} // namespace
