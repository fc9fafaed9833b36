// SPDX-License-Identifier: Apache-2.0
// The "wskpn" and "nbgd" filter types through createFilter (weights as data, rejecting corrupt or
// foreign ones without losing the previous, a small sequence), and their filters' defining
// properties on hand cases: WSKPN with equal weights is a box mean; the bilateral grid keeps a
// constant image and does not blur across a guide edge wider than its range tent.
#include "afn_test_util.h"
#include "base/exception.h"
#include "filter/registry.h"
#include "methods/nbgd/bilateral_grid.h"
#include "methods/wskpn/network.h"
#include "methods/wskpn/weight_sharing_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

namespace {

afn::ImageBinding bind(afn::Image& img)
{
    afn::ImageBinding b;
    b.ptr = img.data();
    b.format = static_cast<AFNFormat>(img.channels());
    b.width = img.width();
    b.height = img.height();
    b.pixelStride = static_cast<std::ptrdiff_t>(img.channels() * sizeof(float));
    b.rowStride = b.pixelStride * img.width();
    return b;
}

std::vector<char> readBytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void runSequence(const std::string& method)
{
    auto f = afn::createFilter(method);
    const int w = 23, h = 13;
    afn::Image color(w, h, 3), albedo(w, h, 3, 0.5f), normal(w, h, 3), depth(w, h, 1), out(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c)
                color(x, y, c) = static_cast<float>(((x * 7 + y * 3 + c) % 5)) * 0.3f;
            normal(x, y, 2) = 1.0f;
            depth(x, y, 0) = 1.0f + 0.1f * static_cast<float>(x);
        }
    f->setImage("color", bind(color));
    f->setImage("albedo", bind(albedo));
    f->setImage("normal", bind(normal));
    f->setImage("depth", bind(depth));
    f->setImage("output", bind(out));
    const std::string other = method == "wskpn" ? "nbgd" : "wskpn";
    const std::string dir = std::string(AFN_TEST_DATA) + "/baselines_parity/";
    const auto bytes = readBytes(dir + method + "_weights.afnw");
    const auto foreign = readBytes(dir + other + "_weights.afnw");
    EXPECT_THROW(f->setData("weights", "garbage", 7), afn::Exception);
    EXPECT_THROW(f->setData("other", bytes.data(), bytes.size()), afn::Exception);
    f->setData("weights", bytes.data(), bytes.size());
    EXPECT_THROW(f->setData("weights", foreign.data(), foreign.size()), afn::Exception);
    f->commit(); // the valid weights survived the failed replacements
    for (int frame = 0; frame < 3; ++frame) {
        f->execute();
        for (std::size_t k = 0; k < out.size(); ++k) {
            ASSERT_TRUE(std::isfinite(out.data()[k])) << method;
            ASSERT_GE(out.data()[k], 0.0f) << method;
        }
    }
}

} // namespace

TEST(BaselineFilters, WskpnRunsWithWeightsAsData)
{
    runSequence("wskpn");
}

TEST(BaselineFilters, NbgdRunsWithWeightsAsData)
{
    runSequence("nbgd");
}

TEST(BaselineFilters, WithoutWeightsCommitSaysSo)
{
    for (const char* method : { "wskpn", "nbgd" }) {
        const afn::FilterType* t = afn::findFilterType(method);
        ASSERT_NE(t, nullptr) << method;
        if (t->ready)
            continue; // this build embeds weights
        auto f = afn::createFilter(method);
        afn::Image color(8, 8, 3, 0.5f), out(8, 8, 3);
        f->setImage("color", bind(color));
        f->setImage("output", bind(out));
        try {
            f->commit();
            FAIL() << method << ": commit without weights must fail";
        } catch (const afn::Exception& e) {
            EXPECT_NE(std::string(e.what()).find("no weights"), std::string::npos) << e.what();
        }
    }
}

TEST(WeightSharingFilter, EqualWeightsGiveBoxMeans)
{
    // All weight logits 0 (w = 1) and fusion only on window 5x5 (logit 30 against 0): the output
    // is the 5x5 mean of the pixels inside the image.
    const int w = 9, h = 7;
    afn::Image color(w, h, 3), head(w, h, afn::wskpn::kHeadChannels, 0.0f), a, b, out;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c)
                color(x, y, c) = static_cast<float>(x * 10 + y + c);
            head(x, y, afn::wskpn::kWindows + 1) = 30.0f;
        }
    afn::wskpn::weightSharingFilter(color, head, a, b, out);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                int n = 0;
                for (int yy = std::max(y - 2, 0); yy <= std::min(y + 2, h - 1); ++yy)
                    for (int xx = std::max(x - 2, 0); xx <= std::min(x + 2, w - 1); ++xx, ++n)
                        sum += color(xx, yy, c);
                EXPECT_NEAR(out(x, y, c), sum / n, 1e-3) << x << "," << y;
            }
}

TEST(BilateralGrid, ConstantStaysAndGuideEdgeIsKept)
{
    const int w = 40, h = 24;
    afn::Image color(w, h, 3), guide(w, h, 1), out;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool right = x >= w / 2;
            for (int c = 0; c < 3; ++c)
                color(x, y, c) = right ? 2.0f : 0.25f;
            guide(x, y, 0) = right ? 200.0f : 20.0f; // 180 apart: many range tents
        }
    afn::nbgd::BilateralGrid grid;
    for (int step : { 4, 8, 16 }) {
        grid.filter(color, guide, 0, step, step, out);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                ASSERT_NEAR(out(x, y, 1), color(x, y, 1), 1e-5) << step << ": " << x << "," << y;
    }
    // The same colour edge with a constant guide is blurred across (the grid is a spatial filter).
    guide.fill(100.0f);
    grid.filter(color, guide, 0, 8, 8, out);
    EXPECT_GT(out(w / 2 - 1, h / 2, 0), 0.3f);
    EXPECT_LT(out(w / 2, h / 2, 0), 1.9f);
}
