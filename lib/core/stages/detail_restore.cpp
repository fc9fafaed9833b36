// SPDX-License-Identifier: Apache-2.0
// Detail restoration (see stages/detail_restore.h for the rule and why).
#include "stages/detail_restore.h"

#include "base/parallel.h"
#include "stages/aux_prefilter.h"
#include "stages/demodulate.h"

#include <algorithm>
#include <cmath>

namespace afn {

const ParamBinding<RestoreSettings>& restoreBinding()
{
    using M = RestoreSettings::Mode;
    static const ParamBinding<RestoreSettings> binding
        = ParamBinding<RestoreSettings>()
              .add(&RestoreSettings::restore, "restore",
                  { { "auto", M::Auto }, { "off", M::Off }, { "on", M::On } }, "Detail restoration",
                  "give the output back the noisy frame's own detail where the output departs "
                  "from it by more than the frame's noise explains (a Wiener shrinkage per pixel "
                  "against the frame's noise, measured on 8x8 blocks; single fireflies are "
                  "clamped to their neighbourhood first): filters made for low sample counts "
                  "remove shading detail along with the noise of a high-spp frame; not in the "
                  "papers. auto: from 16 spp (the spp parameter) and twice the sample count the "
                  "method was made for (afn: its model's; 32 spp for the 16-spp model)")
              .add(&RestoreSettings::noise, "restoreNoise", 0.0, 1000.0, "Restoration noise",
                  "how many times the frame's estimated noise variance the output's local "
                  "departure from the frame must exceed before any of it is given back: larger "
                  "keeps more of the method's output");
    return binding;
}

bool restoreOn(const RestoreSettings& s, int spp, int madeFor)
{
    return s.restore == RestoreSettings::Mode::On
        || (s.restore == RestoreSettings::Mode::Auto && spp >= kAuxTrustedSpp
            && spp >= 2 * madeFor);
}

namespace {

constexpr int kBlock = 8; ///< noise blocks
constexpr int kRadius = 2; ///< 5x5 residual power

/// The remodulation factor of the frame's pixel (stages/demodulate.h), floored for the division.
inline float factorOf(const Frame& f, int x, int y, int k)
{
    return std::max(albedoFactorAt(f, x, y, k), kAlbedoEpsilon);
}

} // namespace

void DetailRestore::run(
    const Image& noisy, const Frame& frame, float noiseScale, const ImageView& output)
{
    const int w = noisy.width(), h = noisy.height();
    const bool divide = !frame.colorDemodulated;
    m_irr.resize(w, h, 3);
    m_residual.resize(w, h, 3);
    m_mean.resize(w, h, 1);
    m_power.resize(w, h, 1);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < 3; ++k)
                    m_irr(x, y, k)
                        = divide ? noisy(x, y, k) / factorOf(frame, x, y, k) : noisy(x, y, k);
    });
    // The clamped irradiance n', its channel mean, the residual r = n' - o and e^2.
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* o = output.at(x, y);
                float e = 0.0f, mean = 0.0f;
                for (int k = 0; k < 3; ++k) {
                    float lo = INFINITY, hi = -INFINITY;
                    for (int qy = std::max(0, y - 1); qy <= std::min(h - 1, y + 1); ++qy)
                        for (int qx = std::max(0, x - 1); qx <= std::min(w - 1, x + 1); ++qx)
                            if (qx != x || qy != y) {
                                lo = std::min(lo, m_irr(qx, qy, k));
                                hi = std::max(hi, m_irr(qx, qy, k));
                            }
                    // The range includes the output's own value: a value that the frame and the
                    // output both put above (or below) the neighbours (a small light, a glint)
                    // is left as the method made it; a firefly the output removed is clamped.
                    const float oi = o[k] / factorOf(frame, x, y, k);
                    const float n = std::clamp(m_irr(x, y, k), std::min(lo, oi), std::max(hi, oi));
                    const float r = n - oi;
                    m_residual(x, y, k) = r;
                    e += r;
                    mean += n;
                }
                e /= 3.0f;
                m_power(x, y, 0) = e * e;
                m_mean(x, y, 0) = mean / 3.0f;
            }
    });
    // s2 per 8x8 block: half the mean squared difference of horizontally adjacent values of
    // mean_c(n'), or of vertically adjacent ones, whichever is smaller.
    const int bw = (w + kBlock - 1) / kBlock, bh = (h + kBlock - 1) / kBlock;
    m_blockNoise.assign(static_cast<std::size_t>(bw) * bh, 0.0f);
    parallelRows(
        bh,
        [&](int by0, int by1) {
            for (int by = by0; by < by1; ++by)
                for (int bx = 0; bx < bw; ++bx) {
                    double across = 0.0, down = 0.0;
                    int n = 0;
                    for (int y = by * kBlock; y < std::min(h, (by + 1) * kBlock); ++y)
                        for (int x = bx * kBlock; x < std::min(w, (bx + 1) * kBlock); ++x) {
                            const double v = m_mean(x, y, 0);
                            if (x + 1 < w) {
                                const double d = m_mean(x + 1, y, 0) - v;
                                across += 0.5 * d * d;
                            }
                            if (y + 1 < h) {
                                const double d = m_mean(x, y + 1, 0) - v;
                                down += 0.5 * d * d;
                            }
                            ++n;
                        }
                    m_blockNoise[static_cast<std::size_t>(by) * bw + bx]
                        = static_cast<float>(std::min(across, down) / n);
                }
        },
        1);
    // The 5x5 mean of e^2 (horizontal sums into m_mean, no longer needed), k, and the output.
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float s = 0.0f;
                for (int qx = std::max(0, x - kRadius); qx <= std::min(w - 1, x + kRadius); ++qx)
                    s += m_power(qx, y, 0);
                m_mean(x, y, 0) = s;
            }
    });
    std::vector<int> restoredRows(static_cast<std::size_t>(h), 0);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const int ya = std::max(0, y - kRadius), yb = std::min(h - 1, y + kRadius);
            for (int x = 0; x < w; ++x) {
                const int xa = std::max(0, x - kRadius), xb = std::min(w - 1, x + kRadius);
                float s = 0.0f;
                for (int qy = ya; qy <= yb; ++qy)
                    s += m_mean(x, qy, 0);
                const float m = s / static_cast<float>((yb - ya + 1) * (xb - xa + 1));
                const float s2
                    = m_blockNoise[static_cast<std::size_t>(y / kBlock) * bw + x / kBlock];
                const float limit = noiseScale * s2;
                if (!(m > limit)) // also m = 0 and NaN: the output as it is
                    continue;
                const float kw = 1.0f - limit / m;
                float* o = output.atMutable(x, y);
                float v[3];
                bool finite = true;
                for (int k = 0; k < 3; ++k) {
                    v[k] = o[k] + kw * m_residual(x, y, k) * factorOf(frame, x, y, k);
                    finite = finite && std::isfinite(v[k]);
                }
                if (!finite)
                    continue;
                std::copy(v, v + 3, o);
                restoredRows[static_cast<std::size_t>(y)] += kw > 0.5f ? 1 : 0;
            }
        }
    });
    long long restored = 0;
    for (int c : restoredRows)
        restored += c;
    m_restoredShare = static_cast<double>(restored) / (static_cast<double>(w) * h);
}

} // namespace afn
