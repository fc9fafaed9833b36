// SPDX-License-Identifier: Apache-2.0
// The --benchmark report's plot and page end to end on the bundled example sequence: one panel
// per metric with a y axis fitted to the data, point labels that do not collide (boxes estimated
// as cli/report_svg.cpp promises), the reference crop first.
#include "cli_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const std::string kSeq = std::string(AFN_EXAMPLES_DIR) + "/sequence/";

std::string readText(const std::string& path)
{
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

/// One report of three methods over three frames (temporal metrics defined), made once.
const std::string& reportDir()
{
    static TempDir dir;
    static const std::string out = [] {
        const std::string o = dir.file("report");
        const CliResult r = runAfntool(
            { "--frames", "0-2", kSeq + "frame.####.exr", "--benchmark:methods=ta,svgf,bmfr",
                "--compare", kSeq + "reference.####.exr", "--report", o, "-q" });
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return o;
    }();
    return out;
}

/// Sequence means per method from results.csv ("mean" rows; the noisy input left out).
std::map<std::string, std::map<std::string, double>> meansOf(const std::string& csv)
{
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    std::stringstream hs(line);
    for (std::string cell; std::getline(hs, cell, ',');)
        header.push_back(cell);
    std::map<std::string, std::map<std::string, double>> out;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream ls(line);
        for (std::string cell; std::getline(ls, cell, ',');)
            cells.push_back(cell);
        if (cells.size() < 3 || cells[2] != "mean" || cells[0] == "noisy input")
            continue;
        for (std::size_t i = 3; i < cells.size() && i < header.size(); ++i)
            out[cells[0]][header[i]] = cells[i].empty() ? NAN : std::stod(cells[i]);
    }
    return out;
}

struct Box {
    double x0, y0, x1, y1;
};

bool overlap(const Box& a, const Box& b)
{
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

} // namespace

TEST(AfntoolReport, OnePanelPerMetricWithAFittedAxis)
{
    if (!fs::exists(kSeq + "reference.0002.exr"))
        GTEST_SKIP() << "examples/sequence not rendered";
    const std::string svg = readText(reportDir() + "/runtime-vs-error.svg");
    const auto means = meansOf(readText(reportDir() + "/results.csv"));
    ASSERT_EQ(means.size(), 3u);
    const std::regex panel("<g class=\"panel\" data-metric=\"([a-zA-Z0-9]+)\" "
                           "data-y-lo=\"([^\"]+)\" data-y-hi=\"([^\"]+)\"");
    std::vector<std::string> metrics;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), panel);
         it != std::sregex_iterator(); ++it) {
        const std::string name = (*it)[1];
        const double lo = std::stod((*it)[2]), hi = std::stod((*it)[3]);
        metrics.push_back(name);
        double dmin = INFINITY, dmax = -INFINITY;
        for (const auto& [label, m] : means)
            dmin = std::min(dmin, m.at(name)), dmax = std::max(dmax, m.at(name));
        ASSERT_TRUE(std::isfinite(dmin)) << name;
        EXPECT_LE(lo, dmin) << name;
        EXPECT_GE(hi, dmax) << name;
        // Fitted: the axis spans at most 2.5 times the data's range (a 0..0.30 axis for data in
        // 0.06..0.14 spans 3.75 times it).
        EXPECT_LE(hi - lo, 2.5 * (dmax - dmin))
            << name << ": axis " << lo << ".." << hi << " for data " << dmin << ".." << dmax;
    }
    EXPECT_EQ(metrics, (std::vector<std::string> { "rmse", "ssim", "tge" }));
}

TEST(AfntoolReport, PointLabelsDoNotCollide)
{
    if (!fs::exists(kSeq + "reference.0002.exr"))
        GTEST_SKIP() << "examples/sequence not rendered";
    const std::string svg = readText(reportDir() + "/runtime-vs-error.svg");
    // Label boxes: 0.65 em per character (cli/report_svg.cpp's bound), 12 px font, baseline y.
    std::vector<Box> labels, points;
    const std::regex label(
        "<text class=\"point-label\" x=\"([-0-9.]+)\" y=\"([-0-9.]+)\"[^>]*>([^<]*)</text>");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label);
         it != std::sregex_iterator(); ++it) {
        const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
        labels.push_back({ x, y - 9.6, x + 0.65 * 12 * (*it)[3].length(), y + 3 });
    }
    const std::regex circle("<circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\" r=\"5\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle);
         it != std::sregex_iterator(); ++it) {
        const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
        points.push_back({ x - 5, y - 5, x + 5, y + 5 });
    }
    // Three methods in three panels: every point is drawn and labelled (they are well apart).
    EXPECT_EQ(points.size(), 9u);
    EXPECT_GE(labels.size(), 9u);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        for (std::size_t j = i + 1; j < labels.size(); ++j)
            EXPECT_FALSE(overlap(labels[i], labels[j])) << "labels " << i << " and " << j;
        for (const Box& p : points)
            EXPECT_FALSE(overlap(labels[i], p)) << "label " << i << " over a point";
    }
}

TEST(AfntoolReport, ReferenceCropComesFirst)
{
    if (!fs::exists(kSeq + "reference.0002.exr"))
        GTEST_SKIP() << "examples/sequence not rendered";
    const std::string html = readText(reportDir() + "/index.html");
    const std::size_t crops = html.find("<div class=crops>");
    ASSERT_NE(crops, std::string::npos);
    const std::size_t caption = html.find("<figcaption>", crops);
    ASSERT_NE(caption, std::string::npos);
    EXPECT_EQ(html.substr(caption + 12, 9), "reference");
}
