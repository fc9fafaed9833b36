// SPDX-License-Identifier: Apache-2.0
// Reprojection and per-tap acceptance (conventions in stages/reproject.h).
#include "stages/reproject.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "stages/reproject_rows.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

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

struct Reprojector::Context {
    const Frame& f;
    bool position; ///< position test (this and the previous frame have positions)
    bool absolute; ///< BMFR's absolute position limit instead of the footprint-relative one
    bool depth; ///< depth test (no positions; both frames have depth)
    bool normal; ///< normal test
};

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

void Reprojector::takeGeometry(Frame& f)
{
    std::swap(m_prevPosition, f.position);
    std::swap(m_prevNormal, f.normal);
    std::swap(m_prevDepth, f.depth);
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

bool Reprojector::accept(const Context& c, int x, int y, int tx, int ty, float& fp) const
{
    const Frame& f = c.f;
    if (tx < 0 || ty < 0 || tx >= f.width || ty >= f.height)
        return false;
    if (c.position) {
        const float d2 = dist2(m_prevPosition.at(tx, ty), f.position.at(x, y));
        if (c.absolute) {
            if (!(d2 < m_settings.positionLimitSquared))
                return false;
        } else if (!(d2 == 0.0f)) {
            if (fp < 0.0f)
                fp = footprint(f, x, y); // once per pixel, and only where a position differs
            const float lim = m_settings.positionLimit * fp;
            if (!(d2 < lim * lim))
                return false;
        }
    } else if (c.depth) {
        const float z = f.depth(x, y, 0);
        const float dz = std::fabs(m_prevDepth(tx, ty, 0) - z);
        if (!(dz == 0.0f || dz < m_settings.depthLimit * std::fabs(z)))
            return false;
    }
    if (c.normal) {
        const float* n = f.normal.at(x, y);
        const float* np = m_prevNormal.at(tx, ty);
        if (isZero3(n) || isZero3(np))
            return false;
        if (!(dist2(n, np) < m_settings.normalLimitSquared))
            return false;
    }
    return true;
}

namespace {

/// Bilinear weights of the four taps for the fractions (fx, fy); shared by acceptance and taps()
/// so that the stored and the rebuilt weights are the same numbers.
inline void bilinearWeights(float fx, float fy, float* bw)
{
    bw[0] = (1.0f - fx) * (1.0f - fy);
    bw[1] = fx * (1.0f - fy);
    bw[2] = (1.0f - fx) * fy;
    bw[3] = fx * fy;
}

} // namespace

Reprojector::TapBits Reprojector::pixelTaps(
    const Context& c, int x, int y, float px, float py) const
{
    TapBits b;
    b.onScreen = 1;
    const float fx0 = std::floor(px), fy0 = std::floor(py);
    const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
    float bw[4];
    bilinearWeights(px - fx0, py - fy0, bw);
    float fp = -1.0f; // footprint, computed on first use
    float ws = 0.0f;
    for (int k = 0; k < 4; ++k) {
        if (!(bw[k] > 0.0f) || !accept(c, x, y, x0 + (k & 1), y0 + (k >> 1), fp))
            continue;
        b.mask |= static_cast<std::uint16_t>(1u << k);
        ws += bw[k];
    }
    if (ws > 0.0f || !m_settings.boxFallback)
        return b;
    // SVGF fallback: 3x3 box around the nearest previous pixel, equal weights.
    const int cx = static_cast<int>(std::floor(px + 0.5f));
    const int cy = static_cast<int>(std::floor(py + 0.5f));
    std::uint16_t mask = 0;
    for (int k = 0; k < 9; ++k)
        if (accept(c, x, y, cx + k % 3 - 1, cy + k / 3 - 1, fp))
            mask |= static_cast<std::uint16_t>(1u << k);
    if (mask) {
        b.box = 1;
        b.mask = mask;
    }
    return b;
}

PixelTaps Reprojector::taps(int x, int y) const
{
    PixelTaps t;
    const std::size_t i = static_cast<std::size_t>(y) * m_width + x;
    const TapBits b = m_bits[i];
    if (!b.onScreen)
        return t;
    float px = static_cast<float>(x), py = static_cast<float>(y);
    if (!m_identityRow[static_cast<std::size_t>(y)]) {
        px = m_prev[i].x;
        py = m_prev[i].y;
    }
    const float fx0 = std::floor(px), fy0 = std::floor(py);
    t.x0 = static_cast<std::int32_t>(fx0);
    t.y0 = static_cast<std::int32_t>(fy0);
    t.fx = px - fx0;
    t.fy = py - fy0;
    t.mask = b.mask;
    t.box = b.box;
    t.onScreen = 1;
    if (b.box) {
        t.x0 = static_cast<std::int32_t>(std::floor(px + 0.5f));
        t.y0 = static_cast<std::int32_t>(std::floor(py + 0.5f));
        return t; // bilinear weights all 0: none was accepted
    }
    float bw[4];
    bilinearWeights(t.fx, t.fy, bw);
    for (int k = 0; k < 4; ++k)
        t.w[k] = (b.mask & (1u << k)) ? bw[k] : 0.0f;
    return t;
}

bool Reprojector::motionRowIsZero(const Frame& f, int y) const
{
    // Branch-free (vectorised) over blocks of 64 values, stopping after the first block with a
    // non-zero value; -0 counts as zero and NaN as non-zero, as m != 0 says.
    const float* m = f.motion.at(0, y);
    const int n = 2 * f.width;
    for (int i0 = 0; i0 < n; i0 += 64) {
        const int i1 = std::min(i0 + 64, n);
        int moving = 0;
        for (int i = i0; i < i1; ++i)
            moving |= static_cast<int>(m[i] != 0.0f);
        if (moving)
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
        m_bits.assign(n, TapBits {});
        m_identityRow.assign(static_cast<std::size_t>(m_height), 1);
        return;
    }
    m_bits.resize(n); // every pixel's taps are rewritten below: no fill pass
    m_identityRow.resize(static_cast<std::size_t>(m_height));
    const bool camera = f.hasPosition() && f.camera.valid && f.prevCamera.valid;
    // Identity rows: zero motion, or no motion and no camera reprojection (static camera).
    std::atomic<bool> anyMoving { false };
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const bool identity = f.hasMotion() ? motionRowIsZero(f, y) : !camera;
            m_identityRow[static_cast<std::size_t>(y)] = identity ? 1 : 0;
            if (!identity)
                anyMoving = true;
        }
    });
    if (anyMoving && m_prev.size() < n)
        m_prev.resize(n);
    const bool position = f.hasPosition() && !m_prevPosition.empty();
    const Context c { f, position, m_settings.positionLimitSquared > 0.0f,
        !position && f.hasDepth() && !m_prevDepth.empty(), f.hasNormal() && !m_prevNormal.empty() };
    // AVX-512 identity rows: the relative position test on packed geometry of this frame's size.
    const bool vector = cpu::activeIsa() == cpu::Isa::Avx512 && c.position && !c.absolute
        && m_prevPosition.sameShape(f.position) && f.position.channels() == 3
        && (!c.normal || (m_prevNormal.sameShape(f.normal) && f.normal.channels() == 3));
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            TapBits* bits = m_bits.data() + static_cast<std::size_t>(y) * m_width;
            if (m_identityRow[static_cast<std::size_t>(y)]) {
                // pixelTaps at prev = (x, y): weights (1, 0, 0, 0), so only the pixel's own tap is
                // tested; the box fallback (rare: the pixel was rejected) takes the general path.
                auto pixel = [&](int x) {
                    TapBits b;
                    b.onScreen = 1;
                    float fp = -1.0f;
                    if (accept(c, x, y, x, y, fp))
                        b.mask = 1;
                    else if (m_settings.boxFallback)
                        b = pixelTaps(c, x, y, static_cast<float>(x), static_cast<float>(y));
                    bits[x] = b;
                };
                int x = 0;
                if (vector) // 16 at a time (reproject_avx512.cpp), the rest as above
                    for (; x + 16 <= f.width; x += 16) {
                        IdentityRow16 r;
                        r.position = f.position.at(x, y);
                        r.prevPosition = m_prevPosition.at(x, y);
                        if (c.normal) {
                            r.normal = f.normal.at(x, y);
                            r.prevNormal = m_prevNormal.at(x, y);
                        }
                        r.testNormal = c.normal;
                        r.normalLimitSquared = m_settings.normalLimitSquared;
                        const IdentityDecision d = identityTaps16(r);
                        // The settled lanes in one store ({1, 0, 1} accepted, {0, 0, 1}
                        // rejected), the others one by one.
                        for (std::uint32_t rest = storeIdentityBits16(
                                 bits + x, d.accepted, d.rejected, m_settings.boxFallback);
                             rest != 0; rest &= rest - 1)
                            pixel(x + __builtin_ctz(rest));
                    }
                for (; x < f.width; ++x)
                    pixel(x);
                continue;
            }
            Prev* prev = m_prev.data() + static_cast<std::size_t>(y) * m_width;
            for (int x = 0; x < f.width; ++x) {
                float px = 0.0f, py = 0.0f;
                bool ok = false;
                previousPosition(f, x, y, px, py, ok);
                prev[x] = { px, py };
                bits[x] = ok ? pixelTaps(c, x, y, px, py) : TapBits {};
            }
        }
    });
}

} // namespace afn
