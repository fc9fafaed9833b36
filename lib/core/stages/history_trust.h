// SPDX-License-Identifier: Apache-2.0
// History trust: where the reprojected history no longer describes the current frame although the
// geometry tests accepted it (a light moved, switched, flickered or faded, a shadow moved, an
// emitter changed, an animated texture), every method that keeps a history shortens or drops it
// there. Shared by the accumulation stage (ta, bmfr, afn, the learned baselines) and svgf's own
// integration; the output TAA of afn, bmfr and svgf follows the same map.
//
// The rule (after A-SVGF's temporal gradients, Schied et al. 2018, and NRD's anti-lag; facts, not
// code): at 1 spp one pixel cannot tell a change from noise, so the test runs on 8x8 blocks. Over
// the pixels of a block whose history was accepted, with l the luminance of the current
// demodulated colour and h that of the reprojected history:
//   mean_c, var_c = mean and variance of l;  mean_h = mean of h;  n = pixels;  L = mean history
//   length, capped at 9 (the accumulation's effective sample count at alphaMin 0.2)
//   noise   = sqrt(var_c / n * (1 + 1 / L))      (standard error of mean_c - mean_h)
//   change  = max(0, |mean_c - mean_h| - 3 * noise) / max(mean_c, mean_h)   (relative, 0..1)
//   trust_b = clamp(1 - 2 * antilag * change, 0, 1)
// so with antilag = 1 a block whose lighting changed by half or more beyond the noise drops its
// history, a 10 % change keeps 80 % of it. The noise term makes the test as sharp as the samples
// allow: at 16-64 spp var_c is small and small changes count; at 1 spp only large ones do. A
// block with fewer than 16 such pixels keeps trust 1 (its pixels mostly start afresh anyway).
// The block trusts are softened towards their 3x3 minimum (0.5 * own + 0.5 * min), so a change
// next to a block also shortens it, and interpolated bilinearly between block centres per pixel.
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

/// Rec. 709 luminance of an RGB triple (the test's signal).
inline float trustLuminance(const float* c)
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

/// Per-pixel trust of a reprojected history, measured per frame (see the file comment).
class HistoryTrust {
public:
    void setSettings(const HistoryTrustSettings& s) { m_antilag = s.antilag; }
    bool enabled() const { return m_antilag > 0.0f; }

    /// Start a frame of w x h. `measure` false (no history, or antilag 0): trust 1 everywhere and
    /// addPixel() must not be called.
    void begin(int width, int height, bool measure);
    /// The sums of row y (for addPixel); rows may be filled by different threads.
    float* rowSums(int y) { return m_rowSums.data() + static_cast<std::size_t>(y) * m_rowStride; }
    /// Add a pixel with accepted history: current luminance l, history luminance h, history
    /// length s (before this frame).
    static void addPixel(float* rowSums, int x, float l, float h, float s)
    {
        float* b = rowSums + (x / kTrustBlock) * kSums;
        b[0] += 1.0f;
        b[1] += l;
        b[2] += l * l;
        b[3] += h;
        b[4] += s;
    }
    /// After every row was added: the block trusts.
    void finish();

    /// False when every pixel of row y has trust 1 (nothing written); else writes the row's
    /// per-pixel trust into out[0 .. width).
    bool rowTrust(int y, float* out) const;
    /// True when some pixel of the frame has trust below 1.
    bool active() const { return m_active; }
    /// Share in [0, 1] of the frame's pixels with accepted history in blocks whose trust fell
    /// below one half ("history cut").
    double cutShare() const { return m_cutShare; }
    /// The per-pixel trust map (1 channel, frame size).
    void map(Image& out) const;

private:
    static constexpr int kSums = 5; ///< count, sum l, sum l^2, sum h, sum s
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
    std::vector<unsigned char> m_blockRowActive; ///< per block row: some trust < 1 in it
};

} // namespace afn
