// SPDX-License-Identifier: Apache-2.0
// The library's frame-size buffers per pixel stay within docs/performance.md's accounting
// ("Memory at 8K"). This program links afntool's heap counter (cli/heap_counter.cpp, the
// replaced global operator new/delete) to count the peak live heap bytes while a filter runs three
// frames. The peak is measured at two frame heights of the same width: the difference per added
// pixel leaves out everything that does not grow with the height (thread pool, weights, afn's
// stripe workspaces, per-row tables), so it is the bytes per pixel of the frame-size buffers alone.
// A method that gains one more frame-size float image (4 bytes per pixel) or more fails here.
#include "afn/afn.hpp"

#include <gtest/gtest.h>

#include "heap_counter.h" // afntool's counting operator new/delete (cli/heap_counter.cpp)

#include <cstdint>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 256;
constexpr double kTrustBlock = 8.0; // stages/history_trust.h
/// SVGF's planes: 32 zero floats each side of a row (methods/svgf/planes.h).
constexpr double kPlaneRow = (32.0 + kWidth + 32.0) / kWidth;

/// The library's frame-size bytes per pixel at the peak, from docs/performance.md's accounting
/// for these inputs (colour, albedo, normal, depth, position, static motion; clean aux), without
/// the caller's output: frame 60, reprojection history and taps 32, the history trust's row sums
/// 5 and block trusts 0.19 (stages/history_trust.h), accumulation 32 (ta, bmfr,
/// afn); svgf's guide 6 planes, integration 2 x 7 planes, colour/variance 5 planes; bmfr's
/// three images of its own; afn's normal01, depth01 and history01 (the shipped full-input models
/// take the history input) and its TAA's history and spare (the 1-spp model runs with taa=auto
/// and postFilter=auto = on, methods/afn/settings.h; the post-filter keeps rings of rows of the
/// width only, post_filter.h, none of the frame's size).
double accountedBytesPerPixel(const std::string& method)
{
    const double trust = 10.0 * 4 / kTrustBlock + 3.0 * 4 / (kTrustBlock * kTrustBlock);
    const double shared = 60 + 32 + trust;
    if (method == "ta")
        return shared + 32;
    if (method == "svgf")
        return shared + (6 + 2 * 7 + 5) * 4 * kPlaneRow;
    if (method == "bmfr")
        return shared + 32 + 3 * 12;
    return shared + 32 + 20 + 2 * 12; // afn
}

/// Peak live heap bytes while a new `method` filter runs three frames of kWidth x height.
std::size_t peakBytes(const std::string& method, int height)
{
    const std::size_t n = static_cast<std::size_t>(kWidth) * height;
    std::vector<float> color(n * 3), albedo(n * 3), normal(n * 3, 0.0f), depth(n, 5.0f);
    std::vector<float> position(n * 3), motion(n * 2, 0.0f), out(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
        const int x = static_cast<int>(i % kWidth), y = static_cast<int>(i / kWidth);
        for (int c = 0; c < 3; ++c)
            albedo[i * 3 + c] = 0.6f - 0.1f * c;
        normal[i * 3 + 2] = 1.0f;
        position[i * 3] = (x + 0.5f) / kWidth * 2.0f - 1.0f;
        position[i * 3 + 1] = 1.0f - (y + 0.5f) / height * 2.0f;
        position[i * 3 + 2] = -5.0f;
    }
    const std::size_t base = afntool::heap::liveBytes();
    afntool::heap::resetPeak();
    {
        afn::DeviceRef device = afn::newDevice();
        device.set("numThreads", 1);
        device.commit();
        afn::FilterRef filter = device.newFilter(method.c_str());
        filter.setImage(AFN_IMAGE_COLOR, color.data(), afn::Format::Float3, kWidth, height);
        filter.setImage(AFN_IMAGE_ALBEDO, albedo.data(), afn::Format::Float3, kWidth, height);
        filter.setImage(AFN_IMAGE_NORMAL, normal.data(), afn::Format::Float3, kWidth, height);
        filter.setImage(AFN_IMAGE_DEPTH, depth.data(), afn::Format::Float, kWidth, height);
        filter.setImage(AFN_IMAGE_POSITION, position.data(), afn::Format::Float3, kWidth, height);
        filter.setImage(AFN_IMAGE_MOTION, motion.data(), afn::Format::Float2, kWidth, height);
        filter.setImage(AFN_IMAGE_OUTPUT, out.data(), afn::Format::Float3, kWidth, height);
        for (int frame = 0; frame < 3; ++frame) {
            std::uint32_t h = 2166136261u + frame;
            for (float& v : color) { // 1-spp-like: mostly dark, rare bright samples
                h = h * 1664525u + 1013904223u;
                const float u = static_cast<float>(h >> 8) / 16777216.0f;
                v = u > 0.9f ? 4.0f * u : 0.3f * u;
            }
            filter.commit();
            filter.execute();
            std::string message;
            EXPECT_EQ(device.getError(&message), afn::Error::None) << method << ": " << message;
        }
    }
    return afntool::heap::peakBytes() - base;
}

class ApiMemory : public testing::TestWithParam<const char*> { };

TEST_P(ApiMemory, FrameSizeBuffersWithinTheAccounting)
{
    const std::string method = GetParam();
    const int h1 = 192, h2 = 384; // both above afn's stripe window (128 rows)
    peakBytes(method, h1); // the first run also makes what the library creates once per process
    const double peak1 = static_cast<double>(peakBytes(method, h1));
    const double peak2 = static_cast<double>(peakBytes(method, h2));
    const double perPixel = (peak2 - peak1) / (static_cast<double>(kWidth) * (h2 - h1));
    const double accounted = accountedBytesPerPixel(method);
    // 1 % for allocator rounding; a further frame-size float image adds 4 bytes per pixel.
    EXPECT_LE(perPixel, accounted * 1.01) << method << ": frame-size bytes per pixel";
    // The accounting names every frame-size buffer: the measurement is not far below it either.
    EXPECT_GE(perPixel, accounted - 4.0)
        << method << ": the accounting lists a buffer that is gone";
}

INSTANTIATE_TEST_SUITE_P(Methods, ApiMemory, testing::Values("ta", "svgf", "bmfr", "afn"),
    [](const testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

} // namespace
