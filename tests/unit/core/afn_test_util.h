// SPDX-License-Identifier: Apache-2.0
// Helpers for the AFN tests: build .afnw archives in memory, read files, load the committed parity
// files, random images and weights.
#pragma once

#include "base/image.h"
#include "nn/weights.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace afntest {

struct NamedTensor {
    std::string name;
    std::vector<std::uint32_t> dims;
    std::vector<float> data;
};

/// Serialise tensors into the .afnw layout (training/afn/weights.py dumps()).
inline std::vector<unsigned char> buildArchive(
    const std::vector<NamedTensor>& ts, const std::string& meta)
{
    std::vector<unsigned char> b;
    auto put = [&](std::uint64_t v, int n) {
        for (int i = 0; i < n; ++i)
            b.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    b = { 'A', 'F', 'N', 'W' };
    put(1, 4);
    put(ts.size(), 4);
    put(meta.size(), 4);
    b.insert(b.end(), meta.begin(), meta.end());
    std::size_t pos = b.size();
    for (const auto& t : ts)
        pos += 2 + t.name.size() + 2 + 4 * t.dims.size() + 16;
    std::vector<std::size_t> offsets;
    for (const auto& t : ts) {
        pos = (pos + 15) / 16 * 16;
        offsets.push_back(pos);
        pos += 4 * t.data.size();
    }
    for (std::size_t k = 0; k < ts.size(); ++k) {
        put(ts[k].name.size(), 2);
        b.insert(b.end(), ts[k].name.begin(), ts[k].name.end());
        b.push_back(1);
        b.push_back(static_cast<unsigned char>(ts[k].dims.size()));
        for (auto d : ts[k].dims)
            put(d, 4);
        put(offsets[k], 8);
        put(4 * ts[k].data.size(), 8);
    }
    for (std::size_t k = 0; k < ts.size(); ++k) {
        b.resize(offsets[k], 0);
        for (float f : ts[k].data) {
            std::uint32_t bits;
            std::memcpy(&bits, &f, 4);
            put(bits, 4);
        }
    }
    return b;
}

inline afn::nn::WeightsArchive parseArchive(
    const std::vector<NamedTensor>& ts, const std::string& meta = "")
{
    const auto b = buildArchive(ts, meta);
    return afn::nn::WeightsArchive::parse(b.data(), b.size(), "in-memory");
}

/// A file's bytes (empty when it cannot be read).
inline std::vector<char> readBytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

inline afn::nn::WeightsArchive loadFile(const std::string& path)
{
    const std::vector<char> bytes = readBytes(path);
    return afn::nn::WeightsArchive::parse(bytes.data(), bytes.size(), path);
}

/// An (H, W, C) tensor of an archive as an image.
inline afn::Image toImage(const afn::nn::WeightTensor& t)
{
    afn::Image img(
        static_cast<int>(t.dims[1]), static_cast<int>(t.dims[0]), static_cast<int>(t.dims[2]));
    std::memcpy(img.data(), t.data.data(), 4 * t.data.size());
    return img;
}

/// A w x h x c image of uniform values in [-1, 1) from mt19937(seed).
inline afn::Image randomImage(int w, int h, int c, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    afn::Image img(w, h, c);
    for (std::size_t k = 0; k < img.size(); ++k)
        img.data()[k] = u(rng);
    return img;
}

/// n uniform values in [-0.5, 0.5) from mt19937(seed) (layer weights and biases).
inline std::vector<float> randomVec(std::size_t n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    std::vector<float> v(n);
    for (float& f : v)
        f = u(rng);
    return v;
}

} // namespace afntest
