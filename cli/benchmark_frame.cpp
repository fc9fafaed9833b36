// SPDX-License-Identifier: Apache-2.0
#include "benchmark_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace afntool {

namespace {

/// Hash noise in [0, 1) for (x, y, frame, channel): integer mixing, independent of thread count.
float hashNoise(std::uint32_t x, std::uint32_t y, std::uint32_t f, std::uint32_t c)
{
    std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ f * 0xcb1ab31fu ^ c * 0x9e3779b9u;
    h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
    return static_cast<float>(h >> 8) / 16777216.0f;
}

afn::io::RoleImage fill(int w, int h, int components, std::initializer_list<float> value)
{
    afn::io::RoleImage r;
    r.width = w, r.height = h, r.components = components;
    r.pixels.resize(static_cast<std::size_t>(w) * h * components);
    const std::vector<float> v(value);
    for (std::size_t i = 0; i < r.pixels.size(); ++i)
        r.pixels[i] = v[i % components];
    return r;
}

} // namespace

int skyRows(int h, double sky)
{
    return std::clamp(static_cast<int>(std::lround(sky * h)), 0, h);
}

void makeFrame(LoadedFrame& f, int w, int h, int frame, double sky)
{
    using afn::io::Role;
    const int rows = skyRows(h, sky);
    if (f.images.roles.empty()) {
        f.images.roles[Role::Color] = fill(w, h, 3, { 0.0f, 0.0f, 0.0f });
        f.images.roles[Role::Albedo] = fill(w, h, 3, { 0.6f, 0.5f, 0.4f });
        f.images.roles[Role::Normal] = fill(w, h, 3, { 0.0f, 0.0f, 1.0f });
        f.images.roles[Role::Depth] = fill(w, h, 1, { 5.0f });
        f.images.roles[Role::Motion] = fill(w, h, 2, { 0.0f, 0.0f });
        afn::io::RoleImage pos = fill(w, h, 3, { 0.0f, 0.0f, -5.0f });
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float* p = &pos.pixels[(static_cast<std::size_t>(y) * w + x) * 3];
                p[0] = (x + 0.5f) / w * 2.0f - 1.0f, p[1] = 1.0f - (y + 0.5f) / h * 2.0f;
                if (y < rows) // sky: far away along the view ray
                    for (int k = 0; k < 3; ++k)
                        p[k] *= kGeneratedSkyDepth / 5.0f;
            }
        f.images.roles[Role::Position] = std::move(pos);
        std::fill_n(f.images.roles[Role::Depth].pixels.begin(), static_cast<std::size_t>(rows) * w,
            kGeneratedSkyDepth);
    }
    f.ref.frame = frame;
    f.ref.path = "generated " + std::to_string(w) + "x" + std::to_string(h);
    f.beauty.resize(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float u = hashNoise(x, y, frame, c);
                float v;
                if (y < rows) // sky: a smooth gradient, nearly noise-free (an environment hit)
                    v = (0.4f + 0.2f * c) * (1.0f - 0.5f * y / h) + 0.01f * u;
                else // mostly dark with rare bright samples, as 1 spp path tracing gives
                    v = u > 0.9f ? 4.0f * u : 0.3f * u;
                f.beauty[(static_cast<std::size_t>(y) * w + x) * 3 + c] = v;
            }
}

} // namespace afntool
