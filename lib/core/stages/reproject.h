// SPDX-License-Identifier: Apache-2.0
// Reprojection of the previous frame onto the current one, with BMFR's per-tap acceptance.
//
// Each pixel's position in the previous frame comes from, in this order of preference:
//   1. motion vectors (Frame::motion, pixels, prev = (x + mx, y + my) in pixel-index space);
//   2. world position + the previous camera (BMFR convention): c = [p, 1] * M_{i-1},
//      uv = (c.xy / c.w + 1) / 2, pix = uv * (W, H) - (off.x, 1 - off.y) with off = the CURRENT
//      frame's pixel offset (BMFR: matrix index i-1, offset index i); c.w <= 0 means no history;
//   3. neither: a static camera is assumed (prev = (x, y)).
// The four bilinear taps around pix (x0 = floor(pix.x), y0 = floor(pix.y), weights from the
// fraction) are accepted one by one (all tests must pass; a test whose buffers are missing is
// skipped):
//   - the tap lies inside the image;
//   - position: |p_prev(tap) - p|^2 < (positionLimit * footprint(p))^2, or the positions are equal.
//     footprint = the world-space size of the current pixel, estimated as max over the two axes of
//     the smaller distance to the left/right (top/bottom) neighbour's position. A scene scaled 10x
//     has 10x larger footprints, so the limit is scene-relative. (BMFR uses absolute per-scene
//     limits, e.g. sponza 0.04 units, which is about 4 footprints at 720p; positionLimitSquared > 0
//     selects that absolute test, |p_prev(tap) - p|^2 < positionLimitSquared, to reproduce BMFR.)
//   - depth (only when there is no position): |z_prev(tap) - z| < depthLimit * z (relative), or
//   equal;
//   - normal: |n_prev(tap) - n|^2 < normalLimitSquared (BMFR: squared distance of the normals,
//     sponza 0.25); a zero normal never matches.
// With only colour and motion, every in-image tap is accepted. Weights of accepted taps are later
// renormalised (gatherHistory). Only taps with a bilinear weight > 0 are tested (a tap of weight 0
// adds nothing to any history: the previous position lies on its column or row), so `mask` holds
// accepted taps of positive weight. Optional SVGF fallback: when no bilinear tap with weight > 0
// is accepted, the 3x3 box around the nearest previous pixel is tested with equal weights.
//
// Static camera (identity reprojection): a row whose motion vectors are all exactly zero (or
// every row, without motion and without a camera reprojection) has prev = (x, y): fx = fy = 0,
// weights (1, 0, 0, 0), so only the pixel's own previous value is tested and fetched. Such rows
// skip reading the motion and computing previous positions; the taps are the ones the general
// rule gives (tests/unit/core/stages/test_reproject_identity.cpp compares the two). The world
// footprint is computed only where a position test needs it (a tap whose position differs).
//
// Storage: per pixel 4 bytes (mask, box, on-screen flag) plus, for rows that are not identity
// rows, the previous position (8 bytes); taps() rebuilds the PixelTaps from them (x0 = floor(px),
// fx = px - x0, weights from fx and fy as computed at acceptance, bit for bit).
#pragma once

#include "base/params.h"
#include "filter/frame.h"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <vector>

namespace afn {

/// Acceptance thresholds (scene-relative, see the file comment).
struct ReprojectSettings {
    /// [0; 1000] position limit in current-pixel footprints (default 4: about BMFR's sponza limit).
    float positionLimit = 4.0f;
    /// [0; 1e6] if > 0: BMFR's absolute limit on the squared position distance (scene units^2,
    /// camera_matrices.h position_limit_squared, sponza 0.0016), replacing positionLimit.
    float positionLimitSquared = 0.0f;
    /// [0; 4] limit on the squared distance of unit normals (BMFR sponza 0.25 = 29 degrees).
    float normalLimitSquared = 0.25f;
    /// [0; 10] relative depth limit |dz| / z, used only without positions (default 0.1).
    float depthLimit = 0.1f;
    /// try a 3x3 box when no bilinear tap survives (SVGF); BMFR and ta do not.
    bool boxFallback = false;
};

/// The taps of one pixel into the previous frame.
struct PixelTaps {
    std::int32_t x0 = 0; ///< bilinear: top-left tap column; box: centre column
    std::int32_t y0 = 0; ///< bilinear: top-left tap row; box: centre row
    float fx = 0.0f; ///< fractional column of the previous position (bilinear)
    float fy = 0.0f; ///< fractional row of the previous position (bilinear)
    float w[4] = {}; ///< bilinear weights of the accepted taps (0 if rejected)
    std::uint16_t mask = 0; ///< accepted taps: bits 0-3 bilinear (TL, TR, BL, BR); box bits 0-8
    std::uint8_t box = 0; ///< 1: 3x3 box fallback with equal weights
    std::uint8_t onScreen = 0; ///< 1: the previous position was computed (TAA may sample it)
};

/// Descriptors of the acceptance thresholds (in the table of every method that reprojects;
/// boxFallback is chosen by the method, not by a parameter).
const ParamBinding<ReprojectSettings>& reprojectBinding();

/// Computes per-pixel taps of each frame against the previous frame's geometry.
class Reprojector {
public:
    void setSettings(const ReprojectSettings& s) { m_settings = s; }
    const ReprojectSettings& settings() const { return m_settings; }

    /// Compute the taps of `frame`; all taps are rejected when there is no previous frame.
    void compute(const Frame& frame);
    /// Keep the frame's geometry for the next compute() (a copy).
    void storeGeometry(const Frame& frame);
    /// Keep the frame's geometry for the next compute() by swapping buffers with `frame`: its
    /// position, normal and depth then hold unspecified data of the same shape (or are empty),
    /// to be overwritten by the next gather (the Filter base, after the method has run).
    void takeGeometry(Frame& frame);
    void reset();

    /// True when the last compute() had a previous frame (its taps may point into it).
    bool hasHistory() const { return m_tapsHaveHistory; }
    /// The taps of pixel (x, y) (decoded from the compact storage, see the file comment).
    PixelTaps taps(int x, int y) const;
    /// True when row y of the last compute() was an identity row (prev = (x, y) for every pixel
    /// with history).
    bool identityRow(int y) const { return m_identityRow[static_cast<std::size_t>(y)] != 0; }
    /// On an identity row (identityRow(y)) with history: true when the pixel's own previous
    /// value was accepted, i.e. taps(x, y) is the single tap (x, y) of weight 1 and
    /// gatherHistory() returns that value itself (0 + 1 * v, divided by 1: v, as the history holds
    /// no -0). Lets the blends skip decoding the taps on a static camera's rows.
    bool ownPixelAccepted(int x, int y) const
    {
        const TapBits& b = m_bits[static_cast<std::size_t>(y) * m_width + x];
        return b.mask == 1 && !b.box;
    }
    /// On an identity row (identityRow(y)) with history: true when the previous position was
    /// computed and did not fall back to the 3x3 box, i.e. taps(x, y) is on screen with bilinear
    /// weights (1, 0, 0, 0) at (x, y), whether or not the tap was accepted (TAA samples it).
    bool ownPixelSampled(int x, int y) const
    {
        const TapBits& b = m_bits[static_cast<std::size_t>(y) * m_width + x];
        return b.onScreen && !b.box;
    }
    /// ownPixelAccepted for the 16 pixels [x, x + 16) of row y, as a mask (bit j: pixel x + j).
    /// AVX-512F only (cpu::activeIsa() == Avx512; stages/reproject_avx512.cpp).
    std::uint32_t ownPixelsAccepted16(int x, int y) const;
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// The geometry taken from the last frame (takeGeometry; empty where it had none).
    const Image& previousNormal() const { return m_prevNormal; }
    const Image& previousDepth() const { return m_prevDepth; }

private:
    /// Per pixel: accepted-tap mask (bits 0-3 bilinear, 0-8 box), box flag, on-screen flag.
    struct TapBits {
        std::uint16_t mask = 0;
        std::uint8_t box = 0;
        std::uint8_t onScreen = 0;
    };
    struct Prev {
        float x = 0.0f, y = 0.0f; ///< previous position (pixel-index space)
    };
    struct Context;

    /// Store the tap bits an identity row's AVX-512 decision settles for the 16 pixels at `bits`
    /// (accepted: the own tap; rejected without the box fallback: none) in one store; returns the
    /// lanes left to the per-pixel test. AVX-512F only (stages/reproject_avx512.cpp).
    static std::uint32_t storeIdentityBits16(
        TapBits* bits, std::uint32_t accepted, std::uint32_t rejected, bool boxFallback);

    void previousPosition(const Frame& f, int x, int y, float& px, float& py, bool& ok) const;
    bool accept(const Context& c, int x, int y, int tx, int ty, float& footprint) const;
    float footprint(const Frame& f, int x, int y) const;
    TapBits pixelTaps(const Context& c, int x, int y, float px, float py) const;
    bool motionRowIsZero(const Frame& f, int y) const;

    ReprojectSettings m_settings;
    std::vector<TapBits> m_bits;
    std::vector<Prev> m_prev; ///< allocated once a frame has a non-identity row
    std::vector<std::uint8_t> m_identityRow;
    int m_width = 0, m_height = 0;
    bool m_hasPrev = false; ///< geometry of a previous frame is stored
    bool m_tapsHaveHistory = false; ///< the current taps were computed against it
    Image m_prevPosition, m_prevNormal, m_prevDepth;
};

/// prev + alpha * (cur - prev), the temporal blend of every method, with a result below FLT_MIN in
/// magnitude flushed to 0: a history decaying to black would otherwise stop at the smallest
/// denormal (alpha times it rounds to 0) and keep every later frame computing on denormals.
inline float blendHistory(float prev, float cur, float alpha)
{
    const float v = prev + alpha * (cur - prev);
    return std::fabs(v) < FLT_MIN ? 0.0f : v;
}

/// Calls visit(x, y, w) for each accepted tap of `t` into the previous frame, in the one order
/// every history gather uses: the bilinear taps with their weights, or the 3x3 box's taps with
/// weight 1. Returns sum(w); 0 means no history.
template <typename Visit> inline float forEachHistoryTap(const PixelTaps& t, Visit&& visit)
{
    float ws = 0.0f;
    if (!t.box) {
        for (int k = 0; k < 4; ++k) {
            if (!(t.mask & (1u << k)) || !(t.w[k] > 0.0f))
                continue;
            visit(t.x0 + (k & 1), t.y0 + (k >> 1), t.w[k]);
            ws += t.w[k];
        }
    } else {
        for (int k = 0; k < 9; ++k) {
            if (!(t.mask & (1u << k)))
                continue;
            visit(t.x0 + k % 3 - 1, t.y0 + k / 3 - 1, 1.0f);
            ws += 1.0f;
        }
    }
    return ws;
}

/// Renormalised history over any storage of the previous frame's values: out[c] = sum(w_k *
/// v_k[c]) / sum(w_k) over the accepted taps of `t`, where `load(x, y, v)` writes the first C
/// channels of pixel (x, y) into v (an Image: gatherHistory; structure-of-arrays planes: svgf).
/// Returns sum(w_k); 0 means no history (out = 0).
template <int C, typename Load>
inline float gatherHistoryWith(const PixelTaps& t, Load&& load, float* out)
{
    for (int c = 0; c < C; ++c)
        out[c] = 0.0f;
    const float ws = forEachHistoryTap(t, [&](int x, int y, float wk) {
        float v[C];
        load(x, y, v);
        for (int c = 0; c < C; ++c)
            out[c] += wk * v[c]; // wk is 1 in the box: the same bits as a plain sum
    });
    if (ws > 0.0f)
        for (int c = 0; c < C; ++c)
            out[c] /= ws;
    return ws;
}

/// gatherHistoryWith for the first C channels of `prev` (the same operations, so the same bits).
template <int C> inline float gatherHistory(const PixelTaps& t, const Image& prev, float* out)
{
    return gatherHistoryWith<C>(
        t,
        [&prev](int x, int y, float* v) {
            const float* p = prev.at(x, y);
            for (int c = 0; c < C; ++c)
                v[c] = p[c];
        },
        out);
}

} // namespace afn
