// SPDX-License-Identifier: Apache-2.0
#include "synthetic_sequence.h"

#include <afn/afn.hpp>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace ofxtest {

namespace {

float hashNoise(int x, int y, int frame, int c)
{
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(frame) * 83492791u
        ^ uint32_t(c) * 2654435761u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h & 0xffffu) / 65535.0f - 0.5f; // [-0.5, 0.5]
}

} // namespace

std::string testWeightsFor(const std::string& method)
{
    if (afn::isFilterTypeReady(method.c_str()))
        return "";
    return std::string(AFN_TEST_DATA) + "/afn_parity/weights_full.afnw";
}

int Sequence::components(const std::string& role)
{
    return role == "normal" || role == "position" ? 3 : role == "depth" ? 1 : 4;
}

std::vector<float> Sequence::plane(const std::string& role, double time, double scale) const
{
    const int k = int(std::lround(time)) - firstFrame;
    const int c = components(role);
    std::vector<float> full(size_t(width) * height * c);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // Scene coordinates of the surface seen at (x, y): the content moves by v per frame.
            const float u = float(x - velocityX * k), v = float(y - velocityY * k);
            float* p = &full[(size_t(y) * width + x) * c];
            const float a[3] = { 0.55f + 0.35f * std::sin(0.21f * u),
                0.5f + 0.3f * std::cos(0.17f * v), 0.45f + 0.25f * std::sin(0.11f * (u + v)) };
            if (role == "color") {
                const float shade = 0.6f + 0.4f * std::cos(0.13f * u) * std::sin(0.19f * v);
                for (int i = 0; i < 3; ++i)
                    p[i] = std::max(0.0f, a[i] * shade * (1.0f + 1.2f * hashNoise(x, y, k, i)));
                p[3] = 0.75f + 0.25f * std::sin(0.3f * u);
            } else if (role == "albedo") {
                for (int i = 0; i < 3; ++i)
                    p[i] = a[i];
                p[3] = 1.0f;
            } else if (role == "normal") {
                const float nx = 0.4f * std::sin(0.2f * u), ny = 0.4f * std::cos(0.15f * v);
                const float len = std::sqrt(nx * nx + ny * ny + 1.0f);
                p[0] = nx / len;
                p[1] = ny / len;
                p[2] = 1.0f / len;
            } else if (role == "depth") {
                p[0] = 4.0f + 0.05f * u + 0.03f * v;
            } else if (role == "position") {
                p[0] = 0.1f * u;
                p[1] = -0.1f * v;
                p[2] = 4.0f + 0.05f * u + 0.03f * v;
            } else if (role == "motion") {
                // To-previous pixel vectors, y up: the surface was velocity pixels back.
                p[0] = float(-velocityX);
                p[1] = float(velocityY);
                p[2] = p[3] = 0.0f;
            } else {
                throw std::invalid_argument("unknown role " + role);
            }
        }
    if (scale == 1.0)
        return full;
    if (scale != 0.5)
        throw std::invalid_argument("scale must be 1 or 0.5");
    const int w = width / 2, h = height / 2;
    std::vector<float> half(size_t(w) * h * c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int i = 0; i < c; ++i) {
                auto at = [&](int dx, int dy) {
                    return full[(size_t(2 * y + dy) * width + 2 * x + dx) * c + i];
                };
                half[(size_t(y) * w + x) * c + i]
                    = 0.25f * (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1));
            }
    return half;
}

ofxhost::ClipSource Sequence::source(const std::string& role) const
{
    ofxhost::ClipSource s;
    s.width = width;
    s.height = height;
    s.components = components(role);
    s.originX = originX;
    s.originY = originY;
    s.firstFrame = firstFrame;
    s.lastFrame = firstFrame + numFrames - 1;
    const Sequence seq = *this;
    s.frame = [seq, role](double time, double scale, std::vector<float>& pixels) {
        if (time < seq.firstFrame || time > seq.firstFrame + seq.numFrames - 1)
            return false;
        pixels = seq.plane(role, time, scale);
        return true;
    };
    return s;
}

std::vector<std::vector<float>> referenceFrames(const Sequence& seq, const ReferenceOptions& opt)
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter(opt.method.c_str());
    if (const std::string path = testWeightsFor(opt.method); !path.empty()) {
        std::ifstream in(path, std::ios::binary);
        const std::vector<char> bytes(
            (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        filter.setData("weights", bytes.data(), bytes.size());
    }
    const int w = int(seq.width * opt.scale), h = int(seq.height * opt.scale);
    std::vector<std::vector<float>> out;
    for (int k = 0; k < seq.numFrames; ++k) {
        const double t = seq.firstFrame + k;
        const std::vector<float> color = seq.plane("color", t, opt.scale);
        filter.setImage(
            "color", const_cast<float*>(color.data()), afn::Format::Float3, w, h, 0, 16);
        filter.setImage(
            "alpha", const_cast<float*>(color.data()) + 3, afn::Format::Float, w, h, 0, 16);
        std::vector<std::vector<float>> aux;
        for (const std::string& role : opt.aux) {
            aux.push_back(seq.plane(role, t, opt.scale));
            const int c = Sequence::components(role);
            const afn::Format f = role == "depth" ? afn::Format::Float
                : role == "motion"                ? afn::Format::Float2
                                                  : afn::Format::Float3;
            filter.setImage(role.c_str(), aux.back().data(), f, w, h, 0, size_t(c) * 4);
        }
        out.emplace_back(size_t(w) * h * 4);
        filter.setImage("output", out.back().data(), afn::Format::Float4, w, h);
        filter.set("motion.yUp", true);
        filter.set("motion.scale", float(opt.scale));
        if (!opt.floatParam.empty())
            filter.set(opt.floatParam.c_str(), float(opt.floatValue));
        if (!opt.stringParam.empty())
            filter.set(opt.stringParam.c_str(), opt.stringValue.c_str());
        if (!opt.temporal || t <= opt.historyStart)
            filter.reset();
        filter.commit();
        filter.execute();
        std::string msg;
        if (device.getError(&msg) != afn::Error::None)
            throw std::runtime_error("reference " + opt.method + ": " + msg);
    }
    return out;
}

} // namespace ofxtest
