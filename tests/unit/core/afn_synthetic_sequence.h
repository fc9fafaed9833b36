// SPDX-License-Identifier: Apache-2.0
// Synthetic render sequences for comparing afn engines (the CPU filter, the CUDA filter and the
// host emulation of the CUDA kernels): generated in memory, deterministic, any size. The scene: a
// textured background the camera pans over by a fraction of a pixel per frame, a box moving
// against it (disocclusions, rejected history), a sky band (depth 1e10, zero normal), a patch of
// zero albedo, noisy HDR colour with fireflies, and a few NaN and negative colour values. Every
// AOV is consistent with the motion: motion vectors, world positions and per-frame cameras
// (orthographic viewProjection matrices in the BMFR convention) reproject to the same place.
#pragma once

#include "base/image.h"
#include "bind_image.h"
#include "filter/filter.h"
#include "filter/work_mask.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace afntest {

/// Which inputs a case binds.
struct SequenceInputs {
    bool albedo = true;
    bool normal = true;
    bool depth = true;
    bool position = true;
    bool motion = true;
    bool camera = false; ///< set viewProjection (reprojection from positions without motion)
    std::string name() const
    {
        std::string n = "color";
        n += albedo ? "+albedo" : "";
        n += normal ? "+normal" : "";
        n += depth ? "+depth" : "";
        n += position ? "+position" : "";
        n += motion ? "+motion" : "";
        n += camera ? "+camera" : "";
        return n;
    }
};

/// One frame's caller buffers (empty images are not bound).
struct SequenceFrame {
    afn::Image color, albedo, normal, depth, position, motion;
    std::vector<float> viewProjection; ///< 16 floats or empty
};

class SyntheticSequence {
public:
    SyntheticSequence(int width, int height, std::uint32_t seed = 1)
        : m_w(width)
        , m_h(height)
        , m_seed(seed)
    {
    }

    SequenceFrame frame(int k, const SequenceInputs& in) const
    {
        SequenceFrame f;
        f.color = afn::Image(m_w, m_h, 3);
        if (in.albedo)
            f.albedo = afn::Image(m_w, m_h, 3);
        if (in.normal)
            f.normal = afn::Image(m_w, m_h, 3);
        if (in.depth)
            f.depth = afn::Image(m_w, m_h, 1);
        if (in.position)
            f.position = afn::Image(m_w, m_h, 3);
        if (in.motion)
            f.motion = afn::Image(m_w, m_h, 2);
        for (int y = 0; y < m_h; ++y)
            for (int x = 0; x < m_w; ++x)
                pixel(k, x, y, f);
        if (in.camera)
            f.viewProjection = camera(k);
        return f;
    }

    /// The orthographic camera of frame k (row-vector convention, clip = [p, 1] * M).
    std::vector<float> camera(int k) const
    {
        std::vector<float> m(16, 0.0f);
        m[0] = 2.0f / (kScale * m_w);
        m[5] = 2.0f / (kScale * m_h);
        m[10] = 0.01f;
        m[12] = -2.0f * k * kPanX / m_w - 1.0f;
        m[13] = -2.0f * k * kPanY / m_h - 1.0f;
        m[15] = 1.0f;
        return m;
    }

private:
    static constexpr float kPanX = 0.7f, kPanY = -0.35f; ///< background motion, pixels/frame
    static constexpr float kScale = 0.05f; ///< world units per pixel
    static constexpr float kBoxVX = 1.6f, kBoxVY = 0.9f; ///< the box's screen motion per frame

    float noise(int x, int y, int k, int c) const
    {
        std::uint32_t h = std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u
            ^ std::uint32_t(k) * 83492791u ^ std::uint32_t(c) * 2654435761u ^ m_seed * 97u;
        h ^= h >> 13;
        h *= 0x5bd1e995u;
        h ^= h >> 15;
        return float(h & 0xffffu) / 65535.0f; // [0, 1]
    }

    void pixel(int k, int x, int y, SequenceFrame& f) const
    {
        const float bx0 = 0.3f * m_w + kBoxVX * k, by0 = 0.35f * m_h + kBoxVY * k;
        const float bw = 0.3f * m_w + 2.0f, bh = 0.3f * m_h + 2.0f;
        const bool box = x >= bx0 && x < bx0 + bw && y >= by0 && y < by0 + bh;
        const bool sky = !box && y < m_h / 8;
        float albedo[3], normal[3], pos[3], depth, motion[2];
        if (box) {
            const float u = x - bx0, v = y - by0; // box-local pixel coordinates
            albedo[0] = 0.8f;
            albedo[1] = 0.3f + 0.2f * std::sin(0.5f * u);
            albedo[2] = 0.2f;
            normal[0] = 0.3f;
            normal[1] = 0.2f * std::cos(0.3f * v);
            normal[2] = -0.9f;
            pos[0] = 100.0f + kScale * u;
            pos[1] = kScale * v;
            pos[2] = 2.0f;
            depth = 2.0f + 0.002f * u;
            motion[0] = -kBoxVX;
            motion[1] = -kBoxVY;
        } else {
            // Scene coordinates of the background point seen at (x, y).
            const float X = kScale * (x + 0.5f + k * kPanX), Y = kScale * (y + 0.5f + k * kPanY);
            const float sx = X / kScale, sy = Y / kScale;
            const bool black = sx > 0.6f * m_w && sx < 0.7f * m_w && sy > 0.7f * m_h;
            albedo[0] = black ? 0.0f : 0.5f + 0.4f * std::sin(0.21f * sx);
            albedo[1] = black ? 0.0f : 0.5f + 0.3f * std::cos(0.17f * sy);
            albedo[2] = black ? 0.0f : 0.45f + 0.25f * std::sin(0.11f * (sx + sy));
            const float nx = 0.4f * std::sin(0.2f * sx), ny = 0.4f * std::cos(0.15f * sy);
            normal[0] = nx;
            normal[1] = ny;
            normal[2] = -1.0f;
            pos[0] = X;
            pos[1] = Y;
            pos[2] = 5.0f + 0.01f * sx;
            depth = 5.0f + 0.01f * sx + 0.005f * sy;
            motion[0] = kPanX;
            motion[1] = kPanY;
            if (sky) {
                normal[0] = normal[1] = normal[2] = 0.0f;
                depth = 1e10f;
                pos[0] = X;
                pos[1] = Y;
                pos[2] = 1e6f;
            }
        }
        const float shade = sky ? 3.0f : 0.4f + 0.6f * std::fabs(std::sin(0.09f * (x + y + 3 * k)));
        for (int c = 0; c < 3; ++c) {
            const float n = noise(x, y, k, c);
            float v = (sky ? 1.0f : albedo[c]) * shade * 2.0f * n;
            if (noise(x, y, k, 7) > 0.995f)
                v *= 60.0f; // firefly
            f.color(x, y, c) = v;
        }
        const float bad = noise(x, y, k, 11);
        if (bad > 0.9992f)
            f.color(x, y, 0) = std::numeric_limits<float>::quiet_NaN();
        else if (bad < 0.0008f)
            f.color(x, y, 1) = -0.5f;
        for (int c = 0; c < 3; ++c) {
            if (!f.albedo.empty())
                f.albedo(x, y, c) = albedo[c];
            if (!f.normal.empty())
                f.normal(x, y, c) = normal[c];
            if (!f.position.empty())
                f.position(x, y, c) = pos[c];
        }
        if (!f.depth.empty())
            f.depth(x, y, 0) = depth;
        if (!f.motion.empty()) {
            f.motion(x, y, 0) = motion[0];
            f.motion(x, y, 1) = motion[1];
        }
    }

    int m_w, m_h;
    std::uint32_t m_seed;
};

/// Bind a frame's non-empty inputs and `out` (3 channels), set its camera, commit and execute.
inline void runFrame(afn::Filter& f, SequenceFrame& in, afn::Image& out)
{
    const char* names[] = { AFN_IMAGE_COLOR, AFN_IMAGE_ALBEDO, AFN_IMAGE_NORMAL, AFN_IMAGE_DEPTH,
        AFN_IMAGE_POSITION, AFN_IMAGE_MOTION };
    afn::Image* images[]
        = { &in.color, &in.albedo, &in.normal, &in.depth, &in.position, &in.motion };
    for (int i = 0; i < 6; ++i)
        if (!images[i]->empty())
            f.setImage(names[i], bindImage(*images[i]));
        else
            f.unsetImage(names[i]);
    f.setImage(AFN_IMAGE_OUTPUT, bindImage(out));
    if (!in.viewProjection.empty())
        f.setFloats(AFN_ARRAY_VIEW_PROJECTION, in.viewProjection);
    f.commit();
    f.execute();
}

/// Gather a sequence's frames as the Filter base does (sanitising, default conventions, the
/// camera and history index), for tests that run the stages or the engines' pieces themselves.
struct FrameGatherer {
    afn::Frame frame;
    bool workSkipping = false; ///< build the work mask (frame.work) as skip=on does
    afn::InputConventions conventions; ///< the inputs' (the filter's conventions parameters)
    afn::Camera prevCamera;
    int index = 0;
    const afn::Frame& gather(SequenceFrame& in)
    {
        std::map<std::string, afn::ImageBinding> images;
        const char* names[] = { AFN_IMAGE_COLOR, AFN_IMAGE_ALBEDO, AFN_IMAGE_NORMAL,
            AFN_IMAGE_DEPTH, AFN_IMAGE_POSITION, AFN_IMAGE_MOTION };
        afn::Image* imgs[]
            = { &in.color, &in.albedo, &in.normal, &in.depth, &in.position, &in.motion };
        for (int i = 0; i < 6; ++i)
            if (!imgs[i]->empty())
                images[names[i]] = bindImage(*imgs[i]);
        afn::InputStats stats;
        afn::gatherFrame(images, conventions, frame, stats);
        if (workSkipping) // the default settings' mask, as Filter::execute builds it
            afn::buildWorkMask(images, afn::WorkSettings {}, frame);
        afn::Camera camera;
        if (!in.viewProjection.empty()) {
            camera.valid = true;
            std::copy(
                in.viewProjection.begin(), in.viewProjection.end(), camera.viewProjection.begin());
        }
        frame.camera = camera;
        frame.prevCamera = index > 0 ? prevCamera : afn::Camera {};
        frame.frameIndex = index++;
        prevCamera = camera;
        return frame;
    }
};

} // namespace afntest
