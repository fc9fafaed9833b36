// SPDX-License-Identifier: Apache-2.0
// History trust from 8x8-block statistics (see stages/history_trust.h).
#include "stages/history_trust.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>

namespace afn {

namespace {

/// Standard errors the change must exceed before it counts.
constexpr float kNoiseSigmas = 3.0f;
/// Relative change ignored: the bias a reprojected, resampled or filtered history keeps (and a
/// lag of a few per cent, which nobody sees), so that static light keeps its whole history.
constexpr double kDeadZone = 0.05;
/// Gain of the relative change: antilag 1 drops the history from a change of one half.
constexpr float kChangeGain = 2.0f;
/// Pixels with accepted history a block needs for the test.
constexpr double kMinPixels = 16.0;
/// Blocks per edge of the coarse level's groups (32x32 pixels).
constexpr int kCoarse = 4;

/// Bilinear position of pixel coordinate p between the centres of blocks: first block index and
/// the weight of the next one, both clamped to [0, count).
inline void blockCoordinate(int p, int count, int& b0, int& b1, float& w)
{
    const float f = (static_cast<float>(p) - 0.5f * (kTrustBlock - 1)) / kTrustBlock;
    if (f <= 0.0f) {
        b0 = b1 = 0;
        w = 0.0f;
        return;
    }
    b0 = std::min(static_cast<int>(f), count - 1);
    b1 = std::min(b0 + 1, count - 1);
    w = b1 == b0 ? 0.0f : f - static_cast<float>(b0);
}

} // namespace

const ParamBinding<HistoryTrustSettings>& historyTrustBinding()
{
    static const ParamBinding<HistoryTrustSettings> binding
        = ParamBinding<HistoryTrustSettings>().add(&HistoryTrustSettings::antilag, "antilag", 0.0,
            4.0, "Anti-lag",
            "history trust: how fast a change of the lighting (a light moved, switched or "
            "flickered, a shadow or an emitter changed) cuts the temporal history where the "
            "geometry still matches, measured per colour channel on 8x8 blocks and 32x32 groups "
            "against their noise. 1: the history is dropped where the lighting changed by 55 % or "
            "more, kept whole below 5 %; 0: never (the original methods, which ghost after a "
            "light switch)");
    return binding;
}

void HistoryTrust::begin(int width, int height, bool measure)
{
    m_width = width;
    m_height = height;
    m_bw = (width + kTrustBlock - 1) / kTrustBlock;
    m_bh = (height + kTrustBlock - 1) / kTrustBlock;
    m_measure = measure && m_antilag > 0.0f;
    m_active = false;
    m_cutShare = 0.0;
    if (!m_measure)
        return;
    m_rowStride = static_cast<std::size_t>(m_bw) * kSums;
    m_rowSums.resize(m_rowStride * static_cast<std::size_t>(height));
    parallelRows(height, [&](int y0, int y1) {
        std::fill(rowSums(y0), rowSums(y0) + (y1 - y0) * m_rowStride, 0.0f);
    });
}

namespace {

/// Trust of one block (or group of blocks) from its sums (HistoryTrust's kSums layout).
double trustOf(const double* s, double antilag)
{
    if (s[0] < kMinPixels)
        return 1.0;
    const double n = s[0];
    double change = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double mc = s[1 + k] / n, mh = s[4 + k] / n, md = mc - mh;
        const double var = std::max(0.0, s[7 + k] / n - md * md); // of the difference c - h
        const double excess = std::fabs(md) - kNoiseSigmas * std::sqrt(var / n);
        change = std::max(change, excess / std::max({ mc, mh, 1e-12 }));
    }
    change = std::max(0.0, change - kDeadZone);
    return std::clamp(1.0 - kChangeGain * antilag * std::min(change, 1.0), 0.0, 1.0);
}

} // namespace

void HistoryTrust::finish()
{
    if (!m_measure)
        return;
    const std::size_t blocks = static_cast<std::size_t>(m_bw) * m_bh;
    m_raw.assign(blocks, 1.0f);
    m_count.assign(blocks, 0.0f);
    // Bands of kCoarse block rows, in parallel: in each, the fine level (8x8 blocks) and the
    // coarse one (groups of kCoarse x kCoarse blocks, 16 times the samples: a quarter of the
    // noise), the lower trust of the two.
    const int bands = (m_bh + kCoarse - 1) / kCoarse;
    parallelFor(bands, [&](int band) {
        const int gy = band * kCoarse;
        const int rows = std::min(kCoarse, m_bh - gy);
        thread_local std::vector<double> sums; // kept by each worker from frame to frame
        sums.assign(static_cast<std::size_t>(m_bw) * kCoarse * kSums, 0.0);
        for (int r = 0; r < rows; ++r)
            for (int bx = 0; bx < m_bw; ++bx) {
                double* s = sums.data() + (static_cast<std::size_t>(r) * m_bw + bx) * kSums;
                const int by = gy + r;
                for (int y = by * kTrustBlock; y < std::min(m_height, (by + 1) * kTrustBlock);
                     ++y) {
                    const float* v = rowSums(y) + static_cast<std::size_t>(bx) * kSums;
                    for (int k = 0; k < kSums; ++k)
                        s[k] += v[k];
                }
                m_count[static_cast<std::size_t>(by) * m_bw + bx] = static_cast<float>(s[0]);
            }
        for (int gx = 0; gx < m_bw; gx += kCoarse) {
            const int cols = std::min(kCoarse, m_bw - gx);
            double g[kSums] = {};
            for (int r = 0; r < rows; ++r)
                for (int bx = gx; bx < gx + cols; ++bx)
                    for (int k = 0; k < kSums; ++k)
                        g[k] += sums[(static_cast<std::size_t>(r) * m_bw + bx) * kSums + k];
            const double coarse = trustOf(g, m_antilag);
            for (int r = 0; r < rows; ++r)
                for (int bx = gx; bx < gx + cols; ++bx) {
                    const double fine = trustOf(
                        sums.data() + (static_cast<std::size_t>(r) * m_bw + bx) * kSums, m_antilag);
                    m_raw[static_cast<std::size_t>(gy + r) * m_bw + bx]
                        = static_cast<float>(std::min(coarse, fine));
                }
        }
    });
    m_columnBlock.resize(static_cast<std::size_t>(m_width));
    m_columnWeight.resize(static_cast<std::size_t>(m_width));
    for (int x = 0; x < m_width; ++x) {
        int bx1;
        blockCoordinate(x, m_bw, m_columnBlock[static_cast<std::size_t>(x)], bx1,
            m_columnWeight[static_cast<std::size_t>(x)]);
    }
    m_block.resize(blocks);
    m_blockRowActive.assign(static_cast<std::size_t>(m_bh), 0);
    double cut = 0.0;
    for (int by = 0; by < m_bh; ++by)
        for (int bx = 0; bx < m_bw; ++bx) {
            float lo = 1.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = bx + dx, qy = by + dy;
                    if (qx >= 0 && qy >= 0 && qx < m_bw && qy < m_bh)
                        lo = std::min(lo, m_raw[static_cast<std::size_t>(qy) * m_bw + qx]);
                }
            const std::size_t i = static_cast<std::size_t>(by) * m_bw + bx;
            const float t = lo == 1.0f ? 1.0f : 0.5f * (m_raw[i] + lo);
            m_block[i] = t;
            if (t < 1.0f) {
                m_active = true;
                m_blockRowActive[static_cast<std::size_t>(by)] = 1;
            }
            if (t < 0.5f)
                cut += m_count[i];
        }
    m_cutShare = cut / (static_cast<double>(m_width) * m_height);
}

void HistoryTrust::interpolateRow(int y, float* out) const
{
    int by0, by1;
    float wy;
    blockCoordinate(y, m_bh, by0, by1, wy);
    // Runs of columns between the same two block centres (m_column: each column's first block
    // and weight): the runs' loops have no lookups and vectorise.
    const float* wx = m_columnWeight.data();
    for (int x0 = 0; x0 < m_width;) {
        const int bx0 = m_columnBlock[static_cast<std::size_t>(x0)];
        int x1 = x0 + 1;
        while (x1 < m_width && m_columnBlock[static_cast<std::size_t>(x1)] == bx0)
            ++x1;
        const int bx1 = std::min(bx0 + 1, m_bw - 1);
        const float t0 = blockAt(bx0, by0), t1 = blockAt(bx1, by0);
        const float b0 = blockAt(bx0, by1), b1 = blockAt(bx1, by1);
        for (int x = x0; x < x1; ++x) {
            const float top = t0 + wx[x] * (t1 - t0);
            const float bottom = b0 + wx[x] * (b1 - b0);
            out[x] = std::clamp(top + wy * (bottom - top), 0.0f, 1.0f);
        }
        x0 = x1;
    }
}

const float* HistoryTrust::rowTrust(int y) const
{
    if (!m_active)
        return nullptr;
    int by0, by1;
    float wy;
    blockCoordinate(y, m_bh, by0, by1, wy);
    if (!m_blockRowActive[static_cast<std::size_t>(by0)]
        && !m_blockRowActive[static_cast<std::size_t>(by1)])
        return nullptr;
    thread_local std::vector<float> row; // kept by each worker from frame to frame
    row.resize(static_cast<std::size_t>(m_width));
    interpolateRow(y, row.data());
    return row.data();
}

void HistoryTrust::map(Image& out) const
{
    out.resize(m_width, m_height, 1);
    for (int y = 0; y < m_height; ++y) {
        float* row = out.at(0, y);
        const float* t = rowTrust(y);
        if (t)
            std::copy(t, t + m_width, row);
        else
            std::fill(row, row + m_width, 1.0f);
    }
}

} // namespace afn
