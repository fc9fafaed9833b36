// SPDX-License-Identifier: Apache-2.0
// Detail restoration (see stages/detail_restore.h for the rule and why).
#include "stages/detail_restore.h"

#include "base/parallel.h"
#include "cpu/target.h"
#include "stages/aux_prefilter.h"
#include "stages/demodulate.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
                  "against the frame's noise, measured on 8x8 blocks; a firefly the output "
                  "removed is clamped to its neighbourhood first): filters made for low sample "
                  "counts "
                  "remove shading detail along with the noise of a high-spp frame; not in the "
                  "papers. auto: from 16 spp (the spp parameter) and twice the sample count the "
                  "method was made for (afn: its model's; 32 spp for the 16-spp model); with "
                  "skip, needed pixels within about 12 px of skipped ones are then not "
                  "bit-identical to skip=off")
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

/// The two blocks whose centres (block * kBlock + 3.5) enclose pixel coordinate v, and the second
/// one's weight; clamped to the first and last block at the image's borders.
inline DetailRestore::BlockLerp blockLerp(int v, int blocks)
{
    const float f = (static_cast<float>(v) - 0.5f * (kBlock - 1)) / kBlock;
    const int i0 = std::clamp(static_cast<int>(std::floor(f)), 0, blocks - 1);
    const int i1 = std::min(i0 + 1, blocks - 1);
    return { i0, i1, std::clamp(f - static_cast<float>(i0), 0.0f, 1.0f) };
}

// The row kernels: branch-free loops over a row's floats, built for AVX-512, AVX2 and the
// baseline, the processor's clone picked at load time (cpu/target.h; clones may differ in the last
// bit, from FMA contraction).

/// The remodulation factors of a row (3 per pixel): max(albedo, kAlbedoEpsilon), the same for a
/// colour already demodulated (stages/demodulate.h: it is remodulated by the plain albedo; the
/// floor only guards the division); 1 without an albedo (albedo null).
AFN_CPU_KERNEL_CLONES void factorsRow(const float* __restrict albedo, int n, float* __restrict out)
{
    if (!albedo) {
        std::fill(out, out + n, 1.0f);
        return;
    }
    for (int i = 0; i < n; ++i)
        out[i] = std::max(albedo[i], kAlbedoEpsilon);
}

/// values / factors, in place.
AFN_CPU_KERNEL_CLONES void divideRow(
    float* __restrict values, const float* __restrict factors, int n)
{
    for (int i = 0; i < n; ++i)
        values[i] /= factors[i];
}

/// lo/hi over the neighbours in row q of each of the row's values (3 floats per pixel): the value
/// above or below and its left and right neighbours (`withCentre`), or only the left and right
/// neighbours (the pixel's own row).
AFN_CPU_KERNEL_CLONES void rangeRow(
    const float* __restrict q, int n, bool withCentre, float* __restrict lo, float* __restrict hi)
{
    if (withCentre)
        for (int i = 0; i < n; ++i) {
            lo[i] = std::min(lo[i], q[i]);
            hi[i] = std::max(hi[i], q[i]);
        }
    for (int i = 3; i < n; ++i) {
        lo[i] = std::min(lo[i], q[i - 3]);
        hi[i] = std::max(hi[i], q[i - 3]);
    }
    for (int i = 0; i + 3 < n; ++i) {
        lo[i] = std::min(lo[i], q[i + 3]);
        hi[i] = std::max(hi[i], q[i + 3]);
    }
}

/// n' = clamp(v, min(lo, o), max(hi, o)) and r = n' - o per value (`ro` holds o and gets r), then
/// per pixel mean_c(n') and (mean_c r)^2.
AFN_CPU_KERNEL_CLONES void residualRow(const float* __restrict v, const float* __restrict lo,
    const float* __restrict hi, int w, float* __restrict ro, float* __restrict mean,
    float* __restrict power)
{
    for (int x = 0; x < w; ++x) {
        float e = 0.0f, m = 0.0f;
        for (int k = 0; k < 3; ++k) {
            const int i = 3 * x + k;
            const float o = ro[i];
            const float n = std::min(std::max(v[i], std::min(lo[i], o)), std::max(hi[i], o));
            ro[i] = n - o;
            e += ro[i];
            m += n;
        }
        e *= 1.0f / 3.0f;
        power[x] = e * e;
        mean[x] = m * (1.0f / 3.0f);
    }
}

/// Sums of p over the 5 columns around each pixel (clipped at the row's ends: the index is clamped
/// so that every load is valid and a tap outside the row adds 0, one branch-free loop).
AFN_CPU_KERNEL_CLONES void boxRow(const float* __restrict p, int w, float* __restrict out)
{
    for (int x = 0; x < w; ++x) {
        float s = 0.0f;
        for (int d = -kRadius; d <= kRadius; ++d) {
            const int q = std::min(std::max(x + d, 0), w - 1);
            s += (x + d >= 0 && x + d < w) ? p[q] : 0.0f;
        }
        out[x] = s;
    }
}

/// k = 1 - limit / m where m > limit (else 0), m the 5x5 mean (`rows`: the window's rows of
/// horizontal 5-column sums, clipped at the image's edges), per pixel; k into kOut.
AFN_CPU_KERNEL_CLONES void weightRow(const float* const* rows, int nRows, int w,
    const float* __restrict limit, float* __restrict kOut)
{
    for (int x = 0; x < w; ++x) {
        float s = 0.0f;
        for (int r = 0; r < nRows; ++r)
            s += rows[r][x];
        const int xa = std::max(0, x - kRadius), xb = std::min(w - 1, x + kRadius);
        const float m = s / static_cast<float>(nRows * (xb - xa + 1));
        kOut[x] = m > limit[x] ? 1.0f - limit[x] / m : 0.0f;
    }
}

/// out += k r f per value (k per pixel, r the residual, f the remodulation factor); a value whose
/// result is not finite keeps the output's.
AFN_CPU_KERNEL_CLONES void giveBackRow(const float* __restrict k, const float* __restrict r,
    const float* __restrict f, int w, float* __restrict out)
{
    for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
            const int i = 3 * x + c;
            const float v = out[i] + k[x] * r[i] * f[i];
            out[i] = v - v == 0.0f ? v : out[i]; // NaN and inf give NaN
        }
}

} // namespace

void DetailRestore::run(Image& noisy, const Frame& frame, float noiseScale, const ImageView& output)
{
    const int w = noisy.width(), h = noisy.height();
    const int n3 = 3 * w;
    const bool divide = !frame.colorDemodulated;
    auto albedoRow = [&](int y) { return frame.hasAlbedo() ? frame.albedo.at(0, y) : nullptr; };
    m_residual.resize(w, h, 3);
    m_mean.resize(w, h, 1);
    m_power.resize(w, h, 1);
    // The frame's irradiance (in place) and the output's (into m_residual).
    parallelRows(h, [&](int y0, int y1) {
        thread_local std::vector<float> factor;
        factor.resize(static_cast<std::size_t>(n3));
        for (int y = y0; y < y1; ++y) {
            factorsRow(albedoRow(y), n3, factor.data());
            float* oi = m_residual.at(0, y);
            for (int x = 0; x < w; ++x) {
                const float* o = output.at(x, y);
                oi[3 * x] = o[0];
                oi[3 * x + 1] = o[1];
                oi[3 * x + 2] = o[2];
            }
            divideRow(oi, factor.data(), n3);
            if (divide)
                divideRow(noisy.at(0, y), factor.data(), n3);
        }
    });
    // n' (the frame's irradiance clamped to its 8 neighbours' range and the output's value; the
    // range includes the output's own value: a value that the frame and the output both put above
    // or below the neighbours, a small light or a glint, is left as the method made it; a firefly
    // the output removed is clamped), r = n' - o, mean_c(n') and (mean_c r)^2. Neighbours outside
    // the image do not count; a 1x1 image's range is the output alone.
    parallelRows(h, [&](int y0, int y1) {
        thread_local std::vector<float> lo, hi;
        lo.resize(static_cast<std::size_t>(n3));
        hi.resize(static_cast<std::size_t>(n3));
        for (int y = y0; y < y1; ++y) {
            std::fill(lo.begin(), lo.end(), INFINITY);
            std::fill(hi.begin(), hi.end(), -INFINITY);
            for (int qy = std::max(0, y - 1); qy <= std::min(h - 1, y + 1); ++qy)
                rangeRow(noisy.at(0, qy), n3, qy != y, lo.data(), hi.data());
            residualRow(noisy.at(0, y), lo.data(), hi.data(), w, m_residual.at(0, y),
                m_mean.at(0, y), m_power.at(0, y));
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
    // The 5x5 mean of e^2: horizontal sums into m_mean (no longer needed), then vertical; k; the
    // output given back k r (remodulated) where k > 0.
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            boxRow(m_power.at(0, y), w, m_mean.at(0, y));
    });
    m_columns.resize(static_cast<std::size_t>(w));
    for (int x = 0; x < w; ++x)
        m_columns[static_cast<std::size_t>(x)] = blockLerp(x, bw);
    m_restoredRows.assign(static_cast<std::size_t>(h), 0);
    parallelRows(h, [&](int y0, int y1) {
        thread_local std::vector<float> factor, limit, weight, row;
        factor.resize(static_cast<std::size_t>(n3));
        row.resize(static_cast<std::size_t>(n3));
        limit.resize(static_cast<std::size_t>(w));
        weight.resize(static_cast<std::size_t>(w));
        for (int y = y0; y < y1; ++y) {
            const int ya = std::max(0, y - kRadius), yb = std::min(h - 1, y + kRadius);
            const float* rows[2 * kRadius + 1];
            for (int q = ya; q <= yb; ++q)
                rows[q - ya] = m_mean.at(0, q);
            // s2 interpolated bilinearly between block centres (a step at each block's edge would
            // show as 8x8 patches of more and less detail).
            const BlockLerp rowLerp = blockLerp(y, bh);
            const float* b0 = m_blockNoise.data() + static_cast<std::size_t>(rowLerp.i0) * bw;
            const float* b1 = m_blockNoise.data() + static_cast<std::size_t>(rowLerp.i1) * bw;
            for (int x = 0; x < w; ++x) {
                const BlockLerp& c = m_columns[static_cast<std::size_t>(x)];
                const float top = b0[c.i0] + c.t * (b0[c.i1] - b0[c.i0]);
                const float bottom = b1[c.i0] + c.t * (b1[c.i1] - b1[c.i0]);
                limit[x] = noiseScale * (top + rowLerp.t * (bottom - top));
            }
            weightRow(rows, yb - ya + 1, w, limit.data(), weight.data());
            factorsRow(albedoRow(y), n3, factor.data());
            for (int x = 0; x < w; ++x) {
                const float* o = output.at(x, y);
                row[3 * x] = o[0];
                row[3 * x + 1] = o[1];
                row[3 * x + 2] = o[2];
            }
            giveBackRow(weight.data(), m_residual.at(0, y), factor.data(), w, row.data());
            int restoredHere = 0;
            for (int x = 0; x < w; ++x) {
                restoredHere += weight[x] > 0.5f ? 1 : 0;
                float* o = output.atMutable(x, y);
                o[0] = row[3 * x];
                o[1] = row[3 * x + 1];
                o[2] = row[3 * x + 2];
            }
            m_restoredRows[static_cast<std::size_t>(y)] = restoredHere;
        }
    });
    long long restored = 0;
    for (int c : m_restoredRows)
        restored += c;
    m_restoredShare = static_cast<double>(restored) / (static_cast<double>(w) * h);
}

} // namespace afn
