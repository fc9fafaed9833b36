// SPDX-License-Identifier: Apache-2.0
// Temporal anti-aliasing (see stages/taa.h). A block of rows keeps a ring of three rows' YCoCg
// planes and their 3-wide min/max; each output row then takes the box and cross bounds from the
// ring, its history from the reprojection, and clamps and blends in one branch-free loop.
#include "stages/taa.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "cpu/target.h"
#include "stages/taa_rows.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace afn {

namespace {

/// YCoCg planes of `rgb` (w pixels, 3 floats each) and their 3-wide min/max.
AFN_CPU_KERNEL_CLONES void yCoCgRow(
    const float* rgb, int w, float* const* v, float* const* lo, float* const* hi)
{
    float* __restrict y = v[0];
    float* __restrict co = v[1];
    float* __restrict cg = v[2];
    for (int x = 0; x < w; ++x) {
        const float r = rgb[3 * x], g = rgb[3 * x + 1], b = rgb[3 * x + 2];
        y[x] = 0.25f * r + 0.5f * g + 0.25f * b;
        co[x] = 0.5f * r - 0.5f * b;
        cg[x] = -0.25f * r + 0.5f * g - 0.25f * b;
    }
    for (int k = 0; k < 3; ++k) {
        const float* __restrict p = v[k];
        float* __restrict l = lo[k];
        float* __restrict h = hi[k];
        if (w == 1) {
            l[0] = h[0] = p[0];
            continue;
        }
        l[0] = std::min(p[0], p[1]);
        h[0] = std::max(p[0], p[1]);
        for (int x = 1; x + 1 < w; ++x) {
            l[x] = std::min(std::min(p[x - 1], p[x]), p[x + 1]);
            h[x] = std::max(std::max(p[x - 1], p[x]), p[x + 1]);
        }
        l[w - 1] = std::min(p[w - 2], p[w - 1]);
        h[w - 1] = std::max(p[w - 2], p[w - 1]);
    }
}

/// Bilinear history at the reprojected position over in-image taps; false if none.
bool sampleHistory(const PixelTaps& t, const Image& history, float* out)
{
    if (!t.onScreen || t.box)
        return false;
    const float bw[4] = { (1.0f - t.fx) * (1.0f - t.fy), t.fx * (1.0f - t.fy), (1.0f - t.fx) * t.fy,
        t.fx * t.fy };
    float ws = 0.0f;
    out[0] = out[1] = out[2] = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const int x = t.x0 + (k & 1), y = t.y0 + (k >> 1);
        if (!(bw[k] > 0.0f) || x < 0 || y < 0 || x >= history.width() || y >= history.height())
            continue;
        const float* h = history.at(x, y);
        for (int c = 0; c < 3; ++c)
            out[c] += bw[k] * h[c];
        ws += bw[k];
    }
    if (!(ws > 0.0f))
        return false;
    for (int c = 0; c < 3; ++c)
        out[c] /= ws;
    return true;
}

} // namespace

void blendRowPortable(const TaaBlendRow& r, int w)
{
    const float alpha = r.alpha;
    const float* __restrict aLo[3] = { r.above->lo[0], r.above->lo[1], r.above->lo[2] };
    const float* __restrict aHi[3] = { r.above->hi[0], r.above->hi[1], r.above->hi[2] };
    const float* __restrict aV[3] = { r.above->v[0], r.above->v[1], r.above->v[2] };
    const float* __restrict cLo[3] = { r.centre->lo[0], r.centre->lo[1], r.centre->lo[2] };
    const float* __restrict cHi[3] = { r.centre->hi[0], r.centre->hi[1], r.centre->hi[2] };
    const float* __restrict bLo[3] = { r.below->lo[0], r.below->lo[1], r.below->lo[2] };
    const float* __restrict bHi[3] = { r.below->hi[0], r.below->hi[1], r.below->hi[2] };
    const float* __restrict bV[3] = { r.below->v[0], r.below->v[1], r.below->v[2] };
    const float* __restrict c0 = r.cur[0];
    const float* __restrict c1 = r.cur[1];
    const float* __restrict c2 = r.cur[2];
    const float* __restrict h0p = r.hist[0];
    const float* __restrict h1p = r.hist[1];
    const float* __restrict h2p = r.hist[2];
    const float* __restrict hasp = r.has;
    float* __restrict o0 = r.out[0];
    float* __restrict o1 = r.out[1];
    float* __restrict o2 = r.out[2];
    for (int x = 0; x < w; ++x) {
        float lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            const float boxLo = std::min(std::min(aLo[k][x], cLo[k][x]), bLo[k][x]);
            const float boxHi = std::max(std::max(aHi[k][x], cHi[k][x]), bHi[k][x]);
            const float crossLo = std::min(std::min(cLo[k][x], aV[k][x]), bV[k][x]);
            const float crossHi = std::max(std::max(cHi[k][x], aV[k][x]), bV[k][x]);
            lo[k] = 0.5f * (boxLo + crossLo);
            hi[k] = 0.5f * (boxHi + crossHi);
        }
        const float h0 = h0p[x], h1 = h1p[x], h2 = h2p[x];
        const float hy[3] = { 0.25f * h0 + 0.5f * h1 + 0.25f * h2, 0.5f * h0 - 0.5f * h2,
            -0.25f * h0 + 0.5f * h1 - 0.25f * h2 };
        float q[3];
        int outside = 0;
        for (int k = 0; k < 3; ++k) {
            const bool below = hy[k]<lo[k], above = hy[k]> hi[k];
            outside |= (below | above) ? 1 : 0;
            q[k] = below ? lo[k] : (above ? hi[k] : hy[k]); // std::clamp's order
        }
        const float hist0 = outside ? q[0] + q[1] - q[2] : h0;
        const float hist1 = outside ? q[0] + q[2] : h1;
        const float hist2 = outside ? q[0] - q[1] - q[2] : h2;
        const bool has = hasp[x] != 0.0f;
        // blendHistory, then std::max(0.0f, v)
        float v0 = hist0 + alpha * (c0[x] - hist0);
        float v1 = hist1 + alpha * (c1[x] - hist1);
        float v2 = hist2 + alpha * (c2[x] - hist2);
        v0 = std::fabs(v0) < FLT_MIN ? 0.0f : v0;
        v1 = std::fabs(v1) < FLT_MIN ? 0.0f : v1;
        v2 = std::fabs(v2) < FLT_MIN ? 0.0f : v2;
        o0[x] = has ? (0.0f < v0 ? v0 : 0.0f) : c0[x];
        o1[x] = has ? (0.0f < v1 ? v1 : 0.0f) : c1[x];
        o2[x] = has ? (0.0f < v2 ? v2 : 0.0f) : c2[x];
    }
}

namespace {

/// Planes of an interleaved RGB row, and back.
AFN_CPU_KERNEL_CLONES void splitRow(const float* __restrict rgb, int w, float* __restrict r,
    float* __restrict g, float* __restrict b)
{
    for (int x = 0; x < w; ++x) {
        r[x] = rgb[3 * x];
        g[x] = rgb[3 * x + 1];
        b[x] = rgb[3 * x + 2];
    }
}

AFN_CPU_KERNEL_CLONES void joinRow(const float* __restrict r, const float* __restrict g,
    const float* __restrict b, int w, float* __restrict rgb)
{
    for (int x = 0; x < w; ++x) {
        rgb[3 * x] = r[x];
        rgb[3 * x + 1] = g[x];
        rgb[3 * x + 2] = b[x];
    }
}

/// Scratch of one block of rows: the ring of three rows, the history planes and the current and
/// output planes of the row, in a per-thread buffer kept between calls (blocks are small; a
/// per-block allocation of this size went through mmap and page faults each frame).
struct RowScratch {
    static constexpr int kPlanes = 3 * 9 + 4 + 6;
    explicit RowScratch(int w)
    {
        thread_local std::vector<float> buffer;
        const std::size_t n = static_cast<std::size_t>(w) * kPlanes;
        if (buffer.size() < n)
            buffer.resize(n);
        float* p = buffer.data();
        for (TaaRingRow& r : ring) {
            for (int k = 0; k < 3; ++k) {
                r.v[k] = p;
                r.lo[k] = p + w;
                r.hi[k] = p + 2 * w;
                p += 3 * w;
            }
        }
        for (float*& h : hist) {
            h = p;
            p += w;
        }
        has = p;
        p += w;
        for (int k = 0; k < 3; ++k) {
            cur[k] = p;
            out[k] = p + w;
            p += 2 * w;
        }
    }
    TaaRingRow ring[3];
    float* hist[3];
    float* has;
    float* cur[3];
    float* out[3];
};

/// Fill the history planes of row y: the pixel's own previous output on a static camera's rows
/// (the bilinear sample's value there), else the bilinear sample.
void historyRow(const Reprojector& taps, const Image& history, int y, int w, RowScratch& s)
{
    const bool identity = taps.identityRow(y);
    for (int x = 0; x < w; ++x) {
        float h[3] = { 0.0f, 0.0f, 0.0f };
        bool has;
        if (identity) {
            has = taps.ownPixelSampled(x, y);
            if (has) {
                const float* p = history.at(x, y);
                h[0] = p[0];
                h[1] = p[1];
                h[2] = p[2];
            }
        } else {
            has = sampleHistory(taps.taps(x, y), history, h); // h stays 0 without history
        }
        for (int k = 0; k < 3; ++k)
            s.hist[k][x] = h[k];
        s.has[x] = has ? 1.0f : 0.0f;
    }
}

constexpr int kRowBlock = 16; ///< rows per parallel block (the ring is rebuilt per block)

} // namespace

void temporalAntialias(
    const Reprojector& taps, const Image& current, const Image& history, float alpha, Image& out)
{
    const int w = current.width(), h = current.height();
    out.resize(w, h, 3);
    const bool haveHistory = taps.hasHistory() && history.width() == w && history.height() == h
        && taps.width() == w && taps.height() == h;
    if (w == 0 || h == 0)
        return;
    if (!haveHistory) {
        std::copy(current.data(), current.data() + current.size(), out.data());
        return;
    }
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    parallelRows(
        h,
        [&](int y0, int y1) {
            RowScratch s(w);
            auto fill = [&](TaaRingRow& r, int y) {
                yCoCgRow(current.at(0, std::clamp(y, 0, h - 1)), w, r.v, r.lo, r.hi);
            };
            // ring[(y + 1) % 3] holds row y (clamped): rows y0 - 1 and y0 first.
            fill(s.ring[y0 % 3], y0 - 1);
            fill(s.ring[(y0 + 1) % 3], y0);
            for (int y = y0; y < y1; ++y) {
                fill(s.ring[(y + 2) % 3], y + 1);
                historyRow(taps, history, y, w, s);
                splitRow(current.at(0, y), w, s.cur[0], s.cur[1], s.cur[2]);
                TaaBlendRow b;
                b.above = &s.ring[y % 3];
                b.centre = &s.ring[(y + 1) % 3];
                b.below = &s.ring[(y + 2) % 3];
                for (int k = 0; k < 3; ++k) {
                    b.cur[k] = s.cur[k];
                    b.hist[k] = s.hist[k];
                    b.out[k] = s.out[k];
                }
                b.has = s.has;
                b.alpha = alpha;
                if (avx512)
                    blendRowAvx512(b, w);
                else
                    blendRowPortable(b, w);
                joinRow(s.out[0], s.out[1], s.out[2], w, out.at(0, y));
            }
        },
        kRowBlock);
}

const Image& TemporalAntialiasing::apply(const Reprojector& taps, const Image& current, float alpha,
    Image& spare, const HistoryTrust* trust)
{
    static const Image kNoHistory; // after a reset: the output is the current frame
    temporalAntialias(taps, current, m_hasHistory ? m_output : kNoHistory, alpha, spare);
    if (m_hasHistory && trust && trust->active())
        // Where the history trust fell, the output moves towards the current frame as a blend
        // factor alpha' = alpha + (1 - alpha) (1 - t) would (stages/history_trust.h).
        parallelRows(spare.height(), [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y) {
                const float* t = trust->rowTrust(y);
                if (!t)
                    continue;
                float* o = spare.at(0, y);
                const float* c = current.at(0, y);
                for (int x = 0; x < spare.width(); ++x)
                    if (t[x] < 1.0f)
                        for (int k = 0; k < 3; ++k)
                            o[3 * x + k] = std::max(
                                0.0f, blendHistory(o[3 * x + k], c[3 * x + k], 1.0f - t[x]));
            }
        });
    std::swap(m_output, spare); // this frame's output is the next frame's history
    m_hasHistory = true;
    return m_output;
}

} // namespace afn
