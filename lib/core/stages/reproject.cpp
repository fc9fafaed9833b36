// SPDX-License-Identifier: Apache-2.0
// Reprojection and per-tap acceptance (conventions in stages/reproject.h).
#include "stages/reproject.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>

namespace afn {

const ParamBinding<ReprojectSettings>& reprojectBinding()
{
    using R = ReprojectSettings;
    static const ParamBinding<R> binding
        = ParamBinding<R>()
              .add(&R::positionLimit, "positionLimit", 0.0, 1000.0, "Position limit",
                  "history tap accepted if its world position is closer than this many pixel "
                  "footprints (world size of the current pixel; scene-relative). BMFR's absolute "
                  "sponza limit 0.04 is about 4 footprints at 720p")
              .add(&R::positionLimitSquared, "positionLimitSquared", 0.0, 1e6,
                  "Absolute position limit (squared)",
                  "if > 0, BMFR's absolute test |p_prev - p|^2 < this (scene units squared, from "
                  "camera_matrices.h: sponza 0.0016, classroom 0.01) replaces positionLimit")
              .add(&R::normalLimitSquared, "normalLimitSquared", 0.0, 4.0, "Normal limit (squared)",
                  "history tap accepted if the squared distance of the unit normals is below this "
                  "(BMFR sponza 0.25, about 29 degrees; unitless)")
              .add(&R::depthLimit, "depthLimit", 0.0, 10.0, "Depth limit",
                  "without positions: history tap accepted if |z_prev - z| < depthLimit * z "
                  "(relative, unitless)");
    return binding;
}

namespace {

inline float dist2(const float* a, const float* b)
{
    const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

inline bool isZero3(const float* v)
{
    return v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f;
}

} // namespace

void Reprojector::reset()
{
    m_hasPrev = false;
    m_tapsHaveHistory = false;
    m_prevPosition = Image();
    m_prevNormal = Image();
    m_prevDepth = Image();
}

void Reprojector::storeGeometry(const Frame& f)
{
    m_prevPosition = f.position;
    m_prevNormal = f.normal;
    m_prevDepth = f.depth;
    m_hasPrev = true;
}

float Reprojector::footprint(const Frame& f, int x, int y) const
{
    const float* p = f.position.at(x, y);
    auto axis = [&](int dx, int dy) {
        float best = -1.0f;
        for (int s = -1; s <= 1; s += 2) {
            const int nx = x + s * dx, ny = y + s * dy;
            if (nx < 0 || ny < 0 || nx >= f.width || ny >= f.height)
                continue;
            const float d = std::sqrt(dist2(p, f.position.at(nx, ny)));
            if (best < 0.0f || d < best)
                best = d;
        }
        return std::max(best, 0.0f);
    };
    return std::max(axis(1, 0), axis(0, 1));
}

void Reprojector::previousPosition(
    const Frame& f, int x, int y, float& px, float& py, bool& ok) const
{
    ok = true;
    if (f.hasMotion()) {
        const float* m = f.motion.at(x, y);
        px = static_cast<float>(x) + m[0];
        py = static_cast<float>(y) + m[1];
    } else if (f.hasPosition() && f.camera.valid && f.prevCamera.valid) {
        const float* p = f.position.at(x, y);
        const auto& M = f.prevCamera.viewProjection;
        const float cx = p[0] * M[0] + p[1] * M[4] + p[2] * M[8] + M[12];
        const float cy = p[0] * M[1] + p[1] * M[5] + p[2] * M[9] + M[13];
        const float cw = p[0] * M[3] + p[1] * M[7] + p[2] * M[11] + M[15];
        if (!(cw > 0.0f)) {
            ok = false;
            return;
        }
        const float u = (cx / cw + 1.0f) * 0.5f, v = (cy / cw + 1.0f) * 0.5f;
        px = u * static_cast<float>(f.width) - f.camera.pixelOffset[0];
        py = v * static_cast<float>(f.height) - (1.0f - f.camera.pixelOffset[1]);
    } else {
        px = static_cast<float>(x);
        py = static_cast<float>(y);
    }
    // Far outside (or non-finite): no history. Keeps the int conversion below defined.
    if (!(std::fabs(px) < 1e7f) || !(std::fabs(py) < 1e7f))
        ok = false;
}

bool Reprojector::accept(const Frame& f, int x, int y, int tx, int ty, float fp) const
{
    if (tx < 0 || ty < 0 || tx >= f.width || ty >= f.height)
        return false;
    if (f.hasPosition() && !m_prevPosition.empty()) {
        const float d2 = dist2(m_prevPosition.at(tx, ty), f.position.at(x, y));
        if (m_settings.positionLimitSquared > 0.0f) {
            if (!(d2 < m_settings.positionLimitSquared))
                return false;
        } else {
            const float lim = m_settings.positionLimit * fp;
            if (!(d2 == 0.0f || d2 < lim * lim))
                return false;
        }
    } else if (f.hasDepth() && !m_prevDepth.empty()) {
        const float z = f.depth(x, y, 0);
        const float dz = std::fabs(m_prevDepth(tx, ty, 0) - z);
        if (!(dz == 0.0f || dz < m_settings.depthLimit * std::fabs(z)))
            return false;
    }
    if (f.hasNormal() && !m_prevNormal.empty()) {
        const float* n = f.normal.at(x, y);
        const float* np = m_prevNormal.at(tx, ty);
        if (isZero3(n) || isZero3(np))
            return false;
        if (!(dist2(n, np) < m_settings.normalLimitSquared))
            return false;
    }
    return true;
}

void Reprojector::compute(const Frame& f)
{
    m_width = f.width;
    m_height = f.height;
    const std::size_t n = static_cast<std::size_t>(m_width) * m_height;
    m_tapsHaveHistory = m_hasPrev;
    // History geometry of another size cannot be used (the base rejects size changes anyway).
    const bool sameSize = (m_prevPosition.empty() || m_prevPosition.width() == f.width)
        && (m_prevNormal.empty() || m_prevNormal.width() == f.width)
        && (m_prevDepth.empty() || m_prevDepth.width() == f.width);
    if (!m_hasPrev || !sameSize) {
        m_taps.assign(n, PixelTaps {});
        return;
    }
    m_taps.resize(n); // every pixel's taps are rewritten below: no fill pass
    const bool usePosition
        = f.hasPosition() && !m_prevPosition.empty() && !(m_settings.positionLimitSquared > 0.0f);
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < f.width; ++x) {
                PixelTaps& t = m_taps[static_cast<std::size_t>(y) * m_width + x];
                t = PixelTaps {};
                float px = 0.0f, py = 0.0f;
                bool ok = false;
                previousPosition(f, x, y, px, py, ok);
                if (!ok)
                    continue;
                const float fx0 = std::floor(px), fy0 = std::floor(py);
                t.x0 = static_cast<std::int32_t>(fx0);
                t.y0 = static_cast<std::int32_t>(fy0);
                t.fx = px - fx0;
                t.fy = py - fy0;
                t.onScreen = 1;
                const float fp = usePosition ? footprint(f, x, y) : 0.0f;
                const float bw[4] = { (1.0f - t.fx) * (1.0f - t.fy), t.fx * (1.0f - t.fy),
                    (1.0f - t.fx) * t.fy, t.fx * t.fy };
                float ws = 0.0f;
                for (int k = 0; k < 4; ++k) {
                    if (!accept(f, x, y, t.x0 + (k & 1), t.y0 + (k >> 1), fp))
                        continue;
                    t.mask |= static_cast<std::uint16_t>(1u << k);
                    t.w[k] = bw[k];
                    ws += bw[k];
                }
                if (ws > 0.0f || !m_settings.boxFallback)
                    continue;
                // SVGF fallback: 3x3 box around the nearest previous pixel, equal weights.
                const int cx = static_cast<int>(std::floor(px + 0.5f));
                const int cy = static_cast<int>(std::floor(py + 0.5f));
                std::uint16_t mask = 0;
                for (int k = 0; k < 9; ++k)
                    if (accept(f, x, y, cx + k % 3 - 1, cy + k / 3 - 1, fp))
                        mask |= static_cast<std::uint16_t>(1u << k);
                if (mask) {
                    t.box = 1;
                    t.mask = mask;
                    t.x0 = cx;
                    t.y0 = cy;
                }
            }
    });
}

} // namespace afn
