// SPDX-License-Identifier: Apache-2.0
// History trust: where the reprojected history no longer describes the current frame although the
// geometry tests accepted it (a light moved, switched, flickered or faded, a shadow moved, an
// emitter changed, an animated texture), every method that keeps a history shortens or drops it
// there. Shared by the accumulation stage (ta, bmfr, afn, the learned baselines) and svgf's own
// integration; the output TAA of afn, bmfr and svgf follows the same map.
//
// The rule (after A-SVGF's temporal gradients, Schied et al. 2018, and NRD's anti-lag; facts, not
// code): at 1 spp one pixel cannot tell a change from noise, so the test runs on 8x8 blocks. Over
// the n pixels of a block whose history was accepted, with c the current demodulated colour and
// h the reprojected history:
//   per channel k:  mc_k, mh_k = means of c_k and h_k;  var_k = variance of c_k - h_k
//   change_k = max(0, |mc_k - mh_k| - 3 sqrt(var_k / n)) / max(mc_k, mh_k)
//             (3 standard errors of the mean difference: the variance of the per-pixel difference
//             holds the noise of both and none of the texture or shading they share, and a
//             firefly on either side raises it, so it does not count as change)
//   trust_b = clamp(1 - 2 * antilag * max(0, max_k change_k - 0.05), 0, 1)
// (changes below 5 % are the bias a resampled or filtered history keeps, not lighting) and the
// same on groups of 4x4 blocks (32x32 pixels: 16 times the samples, a quarter of the
// noise, for the large changes that 1-spp noise hides in one block); a block takes the lower
// trust of its own test and its group's.
// Per channel, so a light that changes colour at the same brightness counts. With antilag = 1 a
// block whose lighting changed by 55 % or more beyond the noise drops its history, a 15 % change
// keeps 80 % of it. The noise term makes the test as sharp as the samples allow: at 16-64 spp the
// variances are small and small changes count; at 1 spp only large ones do. A block with fewer
// than 16 such pixels keeps trust 1 (its pixels mostly start afresh anyway). The block trusts are
// softened towards their 3x3 minimum (0.5 * own + 0.5 * min), so a change next to a block also
// shortens it, and interpolated bilinearly between block centres per pixel.
//
// How a method uses trust t in [0, 1] with its usual blend factor alpha and history length s:
//   alpha' = alpha + (1 - alpha) * (1 - t),   s' = s * t   (then + 1 for this frame)
// t = 1 gives exactly today's arithmetic (bit for bit), t = 0 the current frame alone.
#pragma once

#include "base/image.h"
#include "base/params.h"

#include <vector>

namespace afn {

/// Name of the feature output with the per-pixel trust (every method that reprojects).
constexpr const char* kHistoryTrustFeature = "historyTrust";

/// Edge of the blocks the change is measured on (pixels).
constexpr int kTrustBlock = 8;

/// Settings of the history trust (every method that keeps a history).
struct HistoryTrustSettings {
    float antilag = 1.0f; ///< 0: keep every geometrically valid history (the original methods)
};

/// Descriptors of HistoryTrustSettings (in the table of every method that reprojects).
const ParamBinding<HistoryTrustSettings>& historyTrustBinding();

/// Rec. 709 luminance of an RGB triple (the test's noise is measured on it).
template <typename T> inline T trustLuminance(const T* c)
{
    return T(0.2126) * c[0] + T(0.7152) * c[1] + T(0.0722) * c[2];
}

/// Per-pixel trust of a reprojected history, measured per frame (see the file comment).
class HistoryTrust {
public:
    void setSettings(const HistoryTrustSettings& s) { m_antilag = s.antilag; }
    bool enabled() const { return m_antilag > 0.0f; }

    /// Start a frame of w x h. `measure` false (no history, or antilag 0): trust 1 everywhere and
    /// no pixel may be added.
    void begin(int width, int height, bool measure);
    /// Floats per block of a row's sums: count, sums of c, h and (c - h)^2 (3 channels each).
    static constexpr int kSums = 10;
    /// The sums of row y (for a RowAdder); rows may be filled by different threads.
    float* rowSums(int y) { return m_rowSums.data() + static_cast<std::size_t>(y) * m_rowStride; }

    /// Adds the pixels of one row, left to right, to the row's block sums: a block's sums stay in
    /// registers while its pixels come and are written once, when the row moves to the next
    /// block (bit for bit what adding each pixel to the row's sums gives: they start at 0).
    class RowAdder {
    public:
        /// `rowSums`: rowSums(y), or nullptr to add nothing.
        explicit RowAdder(float* rowSums)
            : m_row(rowSums)
        {
        }
        RowAdder(const RowAdder&) = delete;
        RowAdder& operator=(const RowAdder&) = delete;
        ~RowAdder() { flush(); }
        /// Add pixel x (not left of the last one added) with accepted history: current colour c
        /// and history colour h (3 channels).
        void add(int x, const float* c, const float* h)
        {
            const int block = x / kTrustBlock;
            if (block != m_block) {
                flush();
                m_block = block;
            }
            m_s[0] += 1.0f;
            for (int k = 0; k < 3; ++k) {
                const float d = c[k] - h[k];
                m_s[1 + k] += c[k];
                m_s[4 + k] += h[k];
                m_s[7 + k] += d * d;
            }
        }

        /// The sums of the two whole blocks of pixels [x, x + 16), x a multiple of 16, for the
        /// caller to add those pixels to (they are still 0); nullptr when adding nothing.
        float* wholeBlocks16(int x)
        {
            flush();
            return m_row ? m_row + static_cast<std::size_t>(x / kTrustBlock) * kSums : nullptr;
        }

    private:
        void flush()
        {
            if (m_block < 0)
                return;
            if (m_row) {
                float* b = m_row + static_cast<std::size_t>(m_block) * kSums;
                for (int k = 0; k < kSums; ++k)
                    b[k] += m_s[k];
            }
            for (float& v : m_s)
                v = 0.0f;
            m_block = -1;
        }
        float* m_row;
        int m_block = -1;
        float m_s[kSums] = {};
    };
    /// After every row was added: the block trusts.
    void finish();

    /// nullptr when every pixel of row y has trust 1; else the row's per-pixel trust (width
    /// floats in a buffer of the calling thread, valid until its next call).
    const float* rowTrust(int y) const;
    /// True when some pixel of the frame has trust below 1.
    bool active() const { return m_active; }
    /// Share in [0, 1] of the frame's pixels with accepted history in blocks whose trust fell
    /// below one half ("history cut").
    double cutShare() const { return m_cutShare; }
    /// The per-pixel trust map (1 channel, frame size).
    void map(Image& out) const;

private:
    float blockAt(int bx, int by) const
    {
        return m_block[static_cast<std::size_t>(by) * m_bw + bx];
    }
    void interpolateRow(int y, float* out) const;

    float m_antilag = 1.0f;
    int m_width = 0, m_height = 0, m_bw = 0, m_bh = 0;
    std::size_t m_rowStride = 0;
    bool m_measure = false, m_active = false;
    double m_cutShare = 0.0;
    std::vector<float> m_rowSums; ///< per row and block column: kSums floats
    std::vector<float> m_block; ///< trust per block (after the soft minimum)
    std::vector<float> m_raw; ///< trust per block before it
    std::vector<float> m_count; ///< pixels with history per block
    std::vector<unsigned char> m_blockRowActive; ///< per block row: some trust < 1 in it
    std::vector<int> m_columnBlock; ///< per column: the block centre at or left of it
    std::vector<float> m_columnWeight; ///< and the next centre's bilinear weight
};

} // namespace afn
