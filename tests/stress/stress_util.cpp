// SPDX-License-Identifier: Apache-2.0
#include "stress_util.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

namespace stress {

std::vector<std::string> allMethods()
{
    return afn::filterTypes();
}

std::string testName(const std::string& method)
{
    std::string out = method;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '_';
    return out;
}

const std::vector<Role>& inputRoles()
{
    static const std::vector<Role> roles = {
        { "color", 3, AFN_FORMAT_FLOAT3 },
        { "albedo", 3, AFN_FORMAT_FLOAT3 },
        { "normal", 3, AFN_FORMAT_FLOAT3 },
        { "depth", 1, AFN_FORMAT_FLOAT },
        { "position", 3, AFN_FORMAT_FLOAT3 },
        { "motion", 2, AFN_FORMAT_FLOAT2 },
        { "alpha", 1, AFN_FORMAT_FLOAT },
    };
    return roles;
}

const Role& role(const std::string& name)
{
    for (const Role& r : inputRoles())
        if (r.name == name)
            return r;
    throw std::out_of_range("no input role " + name);
}

namespace {

/// Uniform in [0, 1) from a hash of the arguments (lowbias32).
float hash01(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d)
{
    std::uint32_t h = a * 0x9E3779B1u ^ b * 0x85EBCA77u ^ c * 0xC2B2AE3Du ^ d * 0x27D4EB2Fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return static_cast<float>(h >> 8) / 16777216.0f;
}

FrameData emptyFrame(int w, int h)
{
    FrameData f;
    f.width = w;
    f.height = h;
    for (const Role& r : inputRoles())
        f.planes[r.name].assign(static_cast<std::size_t>(w) * h * r.channels, 0.0f);
    return f;
}

} // namespace

FrameData plausibleFrame(int w, int h, int frame, std::uint32_t seed)
{
    FrameData f = emptyFrame(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const float fx = static_cast<float>(x), fy = static_cast<float>(y);
            const float light = 0.6f + 0.4f * std::sin(0.3f * fx) * std::cos(0.2f * fy);
            for (int c = 0; c < 3; ++c) {
                const float albedo = 0.2f + 0.7f * hash01(x / 4, y / 4, c, seed);
                const float noise = 0.5f
                    + hash01(x, y, c + 3 * static_cast<std::uint32_t>(frame), seed ^ 0x5bd1e995u);
                f.plane("albedo")[i * 3 + c] = albedo;
                f.plane("color")[i * 3 + c] = albedo * light * noise;
            }
            const float nx = 0.1f * std::sin(0.5f * fx), ny = 0.1f * std::cos(0.4f * fy);
            const float inv = 1.0f / std::sqrt(nx * nx + ny * ny + 1.0f);
            f.plane("normal")[i * 3 + 0] = nx * inv;
            f.plane("normal")[i * 3 + 1] = ny * inv;
            f.plane("normal")[i * 3 + 2] = inv;
            f.plane("depth")[i] = 5.0f + 0.01f * fx;
            f.plane("position")[i * 3 + 0] = 0.01f * fx;
            f.plane("position")[i * 3 + 1] = 0.01f * fy;
            f.plane("position")[i * 3 + 2] = 5.0f;
            f.plane("alpha")[i] = 1.0f;
        }
    return f;
}

FrameData constantFrame(int w, int h, float value)
{
    FrameData f = emptyFrame(w, h);
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i) {
        for (int c = 0; c < 3; ++c) {
            f.plane("color")[i * 3 + c] = value;
            f.plane("albedo")[i * 3 + c] = 0.5f;
        }
        f.plane("normal")[i * 3 + 2] = 1.0f;
        f.plane("depth")[i] = 5.0f;
        f.plane("position")[i * 3 + 2] = 5.0f;
        f.plane("alpha")[i] = 1.0f;
    }
    return f;
}

Runner::Runner(const std::string& method, const RunOptions& options)
    : m_method(method)
    , m_options(options)
{
    m_device = afn::newDevice();
    m_device.set("numThreads", options.threads);
    m_device.commit();
    m_filter = m_device.newFilter(method.c_str());
    if (!options.weights.empty())
        m_filter.setData("weights", options.weights.data(), options.weights.size());
    std::string msg;
    if (m_device.getError(&msg) != afn::Error::None)
        m_error = method + ": " + msg;
}

bool Runner::commit()
{
    m_filter.commit();
    std::string msg;
    if (m_device.getError(&msg) == afn::Error::None)
        return true;
    // A learned method in a build without embedded weights: give it the committed test archive.
    if (!m_triedTestWeights && m_options.weights.empty()) {
        m_triedTestWeights = true;
        const std::vector<char> w = readFile(AFN_TEST_DATA "/afn_parity/weights_full.afnw");
        m_filter.setData("weights", w.data(), w.size());
        if (m_device.getError() == afn::Error::None)
            return commit();
    }
    m_error = m_method + ": commit: " + msg;
    return false;
}

bool Runner::run(const FrameData& frame, FrameResult& result)
{
    if (!m_error.empty())
        return false;
    const bool alpha = frame.planes.count("alpha") != 0;
    result.channels = alpha ? 4 : 3;
    result.output.assign(
        static_cast<std::size_t>(frame.width) * frame.height * result.channels, std::nanf(""));
    for (const Role& r : inputRoles()) {
        auto it = frame.planes.find(r.name);
        if (it == frame.planes.end()) {
            m_filter.unsetImage(r.name.c_str());
            continue;
        }
        m_filter.setImage(r.name.c_str(), const_cast<float*>(it->second.data()),
            static_cast<afn::Format>(r.format), frame.width, frame.height);
    }
    m_filter.setImage("output", result.output.data(),
        alpha ? afn::Format::Float4 : afn::Format::Float3, frame.width, frame.height);
    for (const auto& [name, v] : m_options.floats)
        m_filter.set(name.c_str(), v);
    for (const auto& [name, v] : m_options.ints)
        m_filter.set(name.c_str(), v);
    std::string msg;
    if (m_device.getError(&msg) != afn::Error::None) {
        m_error = m_method + ": binding: " + msg;
        return false;
    }
    if (!commit())
        return false;
    m_filter.execute();
    if (m_device.getError(&msg) != afn::Error::None) {
        m_error = m_method + ": execute: " + msg;
        return false;
    }
    result.nonFinite = m_filter.get<int>("stats.nonFinite");
    result.negative = m_filter.get<int>("stats.negative");
    return true;
}

std::vector<FrameResult> runSequence(const std::string& method,
    const std::vector<FrameData>& frames, const RunOptions& options, std::string* error)
{
    Runner runner(method, options);
    std::vector<FrameResult> out;
    for (const FrameData& f : frames) {
        FrameResult r;
        if (!runner.run(f, r)) {
            if (error)
                *error = runner.error();
            return out;
        }
        out.push_back(std::move(r));
    }
    if (error)
        error->clear();
    return out;
}

bool takesWeights(const std::string& method)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter(method.c_str());
    const std::vector<char> w = readFile(AFN_TEST_DATA "/afn_parity/weights_full.afnw");
    filter.setData("weights", w.data(), w.size());
    return device.getError() == afn::Error::None;
}

bool hasIntParameter(const std::string& method, const std::string& name)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter(method.c_str());
    filter.set(name.c_str(), 1);
    return device.getError() == afn::Error::None;
}

long long countNonFinite(const FrameData& frame)
{
    long long n = 0;
    for (const auto& [name, plane] : frame.planes)
        for (float v : plane)
            n += std::isfinite(v) ? 0 : 1;
    return n;
}

long long countNegativeColor(const FrameData& frame)
{
    long long n = 0;
    for (float v : frame.plane("color"))
        n += std::isfinite(v) && v < 0.0f ? 1 : 0;
    return n;
}

double sanitisedColorMean(const FrameData& frame, double cap)
{
    const std::vector<float>& c = frame.plane("color");
    double sum = 0.0;
    for (float v : c)
        sum += std::isfinite(v) && v > 0.0f ? std::min(static_cast<double>(v), cap) : 0.0;
    return c.empty() ? 0.0 : sum / static_cast<double>(c.size());
}

double outputMean(const FrameResult& r)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < r.output.size(); i += r.channels)
        for (int c = 0; c < 3; ++c, ++n)
            sum += r.output[i + c];
    return n ? sum / static_cast<double>(n) : 0.0;
}

bool allFinite(const std::vector<float>& v, std::string* where)
{
    for (std::size_t i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i])) {
            if (where)
                *where = "value " + std::to_string(i) + " is " + std::to_string(v[i]);
            return false;
        }
    return true;
}

bool bitIdentical(const std::vector<float>& a, const std::vector<float>& b, std::string* where)
{
    if (a.size() != b.size()) {
        if (where)
            *where = "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
        return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) {
            if (where)
                *where = "value " + std::to_string(i) + ": " + std::to_string(a[i]) + " vs "
                    + std::to_string(b[i]);
            return false;
        }
    return true;
}

std::vector<char> readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::vector<char>(
        (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

} // namespace stress
