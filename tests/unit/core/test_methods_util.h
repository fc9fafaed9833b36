// SPDX-License-Identifier: Apache-2.0
// Helpers for the methods tests: synthetic buffers, binding them to a Filter, frame runs, RMSE.
#pragma once

#include "base/image.h"
#include "bind_image.h"
#include "filter/frame.h"
#include "filter/registry.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace methods_test {

using afn::Image;

/// One frame's caller buffers; empty images are not bound.
struct Buffers {
    Image color, albedo, normal, depth, position, motion, out;
    std::vector<float> viewProjection; ///< 16 floats, or empty
};

/// Bind every non-empty buffer (and the output, allocated here), set the camera, commit, execute.
inline void runFrame(afn::Filter& f, Buffers& b)
{
    if (b.out.empty())
        b.out = Image(b.color.width(), b.color.height(), 3);
    const char* names[] = { "color", "albedo", "normal", "depth", "position", "motion" };
    Image* imgs[] = { &b.color, &b.albedo, &b.normal, &b.depth, &b.position, &b.motion };
    for (int i = 0; i < 6; ++i)
        if (!imgs[i]->empty())
            f.setImage(names[i], afntest::bindImage(*imgs[i]));
    f.setImage("output", afntest::bindImage(b.out));
    if (!b.viewProjection.empty())
        f.setFloats("viewProjection", b.viewProjection);
    f.commit();
    f.execute();
}

/// Deterministic uniform values in [-1, 1) (LCG; independent of the library).
struct Lcg {
    std::uint32_t s;
    float next()
    {
        s = s * 1664525u + 1013904223u;
        return static_cast<float>(s >> 8) / 8388608.0f - 1.0f;
    }
};

inline double rmse(const Image& a, const Image& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = static_cast<double>(a.data()[i]) - b.data()[i];
        sum += d * d;
    }
    return std::sqrt(sum / static_cast<double>(a.size()));
}

inline bool allFiniteNonNegative(const Image& a)
{
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!std::isfinite(a.data()[i]) || a.data()[i] < 0.0f)
            return false;
    return true;
}

inline bool bitEqual(const Image& a, const Image& b)
{
    if (a.size() != b.size())
        return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a.data()[i] != b.data()[i])
            return false;
    return true;
}

/// Image filled per pixel by fn(x, y, c).
template <typename Fn> Image makeImage(int w, int h, int ch, Fn fn)
{
    Image img(w, h, ch);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                img(x, y, c) = fn(x, y, c);
    return img;
}

/// Row-vector view-projection (BMFR convention) of an orthographic camera shifted by (tx, ty):
/// the world point (px, py, *) lands on pixel index (px + tx - 0.5, py + ty - 0.5) with the default
/// pixel offset (0.5, 0.5). Dyadic for power-of-two sizes, so whole shifts are exact.
inline std::vector<float> shiftedCamera(int w, int h, float tx, float ty)
{
    std::vector<float> m(16, 0.0f);
    m[0 * 4 + 0] = 2.0f / static_cast<float>(w);
    m[1 * 4 + 1] = 2.0f / static_cast<float>(h);
    m[2 * 4 + 2] = 1.0f;
    m[3 * 4 + 0] = 2.0f * tx / static_cast<float>(w) - 1.0f;
    m[3 * 4 + 1] = 2.0f * ty / static_cast<float>(h) - 1.0f;
    m[3 * 4 + 3] = 1.0f;
    return m;
}

/// A static camera's w x h frame for the kernels' AVX-512 against portable tests: positions fixed,
/// about 7 % of the pixels moved this frame (their own previous pixel is rejected, so 16-pixel
/// blocks mix both paths), colour with black pixels (every 11th column) and, in row 0, values
/// whose temporal blend underflows below FLT_MIN; albedo 1, normals +z, no motion. `seed` picks the
/// frame's random values (a test passes a different one per frame).
inline afn::Frame staticCameraFrame(int w, int h, std::uint32_t seed)
{
    Lcg rng { seed };
    afn::Frame f;
    f.width = w;
    f.height = h;
    f.color = Image(w, h, 3);
    f.albedo = Image(w, h, 3, 1.0f);
    f.position = Image(w, h, 3);
    f.normal = Image(w, h, 3, 0.0f);
    f.motion = Image(w, h, 2, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float r = rng.next();
            f.position(x, y, 0) = 0.1f * x;
            f.position(x, y, 1) = 0.1f * y;
            f.position(x, y, 2) = r > 0.93f ? 3.0f : 0.0f; // moved: history restarts there
            f.normal(x, y, 2) = 1.0f;
            for (int c = 0; c < 3; ++c) {
                const float q = std::fabs(rng.next());
                f.color(x, y, c) = y == 0 ? 3e-38f * q : (x % 11 == 0 ? 0.0f : 4.0f * q);
            }
        }
    return f;
}

/// staticCameraFrame for frame `t` of a sequence whose left half turns 3 times brighter on every
/// 7th frame (t % 7 == 6): the history trust cuts the history of those blocks, not the others'.
inline afn::Frame staticCameraFrameWithLightJumps(int w, int h, std::uint32_t seed, int t)
{
    afn::Frame f = staticCameraFrame(w, h, seed);
    if (t % 7 == 6)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w / 2; ++x)
                for (int c = 0; c < 3; ++c)
                    f.color(x, y, c) *= 3.0f;
    return f;
}

} // namespace methods_test
