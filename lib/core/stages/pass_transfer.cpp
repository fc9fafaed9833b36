// SPDX-License-Identifier: Apache-2.0
#include "stages/pass_transfer.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace afn {
namespace {

/// Edge stops of the shared filter (see pass_transfer.h): luminance difference of the denoised
/// beauty relative to the centre pixel's, normal cosine^16, relative depth difference per a-trous
/// step.
constexpr float kLumaSigma = 0.2f;
constexpr float kDepthSigma = 0.02f;
/// The guide planes (PassTransfer::m_guide, each w x h): luminance, normal xyz, depth, then the
/// centre pixel's scales 1 / (kLumaSigma lum + 1e-4) and 1 / (kDepthSigma |depth| + 1e-6).
enum Plane { Luma, Nx, Ny, Nz, Depth, LumaScale, DepthScale, kGuide };
/// A filtered beauty at or below this is black: the gain is 1 there.
constexpr float kBlack = 1e-12f;
/// The smallest factor through which a black neighbourhood's B' is put into a pass.
constexpr float kFallbackFactor = 0.01f;

/// NaN/Inf and negatives as 0, as the methods read their colour.
float sanitize(float v)
{
    return std::isfinite(v) && v > 0.0f ? v : 0.0f;
}

/// exp(-x) for x >= 0 to 6e-5 relative (2^-t: the integer part in the exponent bits, the fraction
/// by a polynomial); x is clamped at 87 (exp(-87) = 1.6e-38, a normal float). The weights only need
/// to be the same for every image of the stack, not exact: the filter's linearity does not depend
/// on them.
inline float expNeg(float x)
{
    const float t = (x < 87.0f ? x : 87.0f) * 1.44269504f; // log2(e)
    // t = i + f with i = round(t) (the 1.5 x 2^23 trick: no float-to-int conversion, so that the
    // loops vectorise) and |f| <= 1/2; 2^-f by its Taylor series (error below 6e-5).
    constexpr float kMagic = 12582912.0f;
    const float r = t + kMagic;
    const std::int32_t i
        = __builtin_bit_cast(std::int32_t, r) - __builtin_bit_cast(std::int32_t, kMagic);
    const float f = t - (r - kMagic);
    const float p = 1.0f + f * (-0.693147f + f * (0.240227f + f * (-0.0555041f + f * 0.00961813f)));
    return p * __builtin_bit_cast(float, static_cast<std::int32_t>((127 - i) << 23));
}

/// Weights of the tap (dx, row q) for the pixels [xs, xe) of row p: hk x exp(-(|dl| sl + |dz| sz /
/// step)) x cos^16, from the planes of the two rows (one branch-free loop, so that it vectorises).
/// Built for AVX-512 and for the baseline; the processor picks at load time (GCC function clones).
#define AFN_PASS_CLONES __attribute__((target_clones("avx512f", "default")))

AFN_PASS_CLONES void weightRow(bool normals, bool depth, const float* const* p,
    const float* const* q, int dx, int xs, int xe, float hk, float depthScale,
    float* __restrict wrow)
{
    const float* __restrict pl = p[Luma];
    const float* __restrict ps = p[LumaScale];
    const float* __restrict pz = p[Depth];
    const float* __restrict pzs = p[DepthScale];
    const float* __restrict px = p[Nx];
    const float* __restrict py = p[Ny];
    const float* __restrict pn = p[Nz];
    const float* __restrict ql = q[Luma] + dx;
    const float* __restrict qz = q[Depth] + dx;
    const float* __restrict qx = q[Nx] + dx;
    const float* __restrict qy = q[Ny] + dx;
    const float* __restrict qn = q[Nz] + dx;
    // Absent guides are planes of 0 (finite): their terms are switched off arithmetically.
    const float depthOn = depth ? depthScale : 0.0f;
    const float normalOn = normals ? 1.0f : 0.0f;
    for (int x = xs; x < xe; ++x) {
        const float e
            = std::fabs(pl[x] - ql[x]) * ps[x] + std::fabs(pz[x] - qz[x]) * pzs[x] * depthOn;
        const float dot = px[x] * qx[x] + py[x] * qy[x] + pn[x] * qn[x];
        const float d = dot > 0.0f ? dot : 0.0f;
        const float d2 = d * d, d4 = d2 * d2, d8 = d4 * d4;
        wrow[x] = hk * expNeg(e) * (1.0f - normalOn + normalOn * (d8 * d8));
    }
}

/// acc[x][c] += w[x] v[x][c], wsum[x] += w[x] for the pixels [xs, xe) of a row of C channels.
AFN_PASS_CLONES void accumulateRow(const float* __restrict w, const float* __restrict v,
    float* __restrict acc, float* __restrict wsum, int xs, int xe, std::size_t C)
{
    for (int x = xs; x < xe; ++x) {
        const float wq = w[x];
        float* a = acc + static_cast<std::size_t>(x) * C;
        const float* vx = v + static_cast<std::size_t>(x) * C;
        for (std::size_t c = 0; c < C; ++c)
            a[c] += wq * vx[c];
        wsum[x] += wq;
    }
}

} // namespace

void PassTransfer::filterSpatial(const PassGuides& g, int channels)
{
    static const float h[5] = { 1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16 };
    const int w = m_stack.width(), ht = m_stack.height();
    const bool normals = !g.normal.empty(), depth = !g.depth.empty();
    m_scratch.resize(w, ht, channels);
    Image* src = &m_stack;
    Image* dst = &m_scratch;
    const std::size_t C = static_cast<std::size_t>(channels);
    auto row = [&](int k, int y) {
        return m_guide.data()
            + (static_cast<std::size_t>(k) * ht + y) * static_cast<std::size_t>(w);
    };
    for (int level = 0; level < kLevels; ++level) {
        const int step = 1 << level;
        const float depthScale = 1.0f / static_cast<float>(step);
        // Row by row: for each of the 25 taps, the weights of the whole row, then the stack's
        // channels accumulated with them (contiguous, so the loops vectorise).
        parallelRows(ht, [&](int y0, int y1) {
            // One row of tap weights and of their sums, kept by each worker from frame to frame.
            thread_local std::vector<float> weights, sums;
            weights.resize(static_cast<std::size_t>(w));
            sums.resize(static_cast<std::size_t>(w));
            float* wr = weights.data();
            float* wsum = sums.data();
            for (int y = y0; y < y1; ++y) {
                // The output row holds the weighted sums until they are normalised.
                float* acc = dst->at(0, y);
                std::fill(acc, acc + static_cast<std::size_t>(w) * C, 0.0f);
                std::fill(wsum, wsum + w, 0.0f);
                const float* py[kGuide];
                for (int k = 0; k < kGuide; ++k)
                    py[k] = row(k, y);
                for (int j = -2; j <= 2; ++j) {
                    const int qy = y + j * step;
                    if (qy < 0 || qy >= ht)
                        continue;
                    const float* pq[kGuide];
                    for (int k = 0; k < kGuide; ++k)
                        pq[k] = row(k, qy);
                    for (int i = -2; i <= 2; ++i) {
                        const int dx = i * step;
                        const int xs = std::max(0, -dx), xe = std::min(w, w - dx);
                        const float hk = h[i + 2] * h[j + 2];
                        if (i == 0 && j == 0)
                            std::fill(wr + xs, wr + xe, hk);
                        else
                            weightRow(normals, depth, py, pq, dx, xs, xe, hk, depthScale, wr);
                        const float* v
                            = src->at(0, qy) + static_cast<std::ptrdiff_t>(dx) * channels;
                        accumulateRow(wr, v, acc, wsum, xs, xe, C);
                    }
                }
                for (int x = 0; x < w; ++x) {
                    const float inv = 1.0f / wsum[x]; // the centre tap is always in: wsum > 0
                    for (std::size_t c = 0; c < C; ++c)
                        acc[static_cast<std::size_t>(x) * C + c] *= inv;
                }
            }
        });
        std::swap(src, dst);
    }
    if (src != &m_stack)
        std::swap(m_stack, m_scratch);
}

void PassTransfer::accumulate(const PassGuides& g, bool useHistory)
{
    const int w = m_stack.width(), ht = m_stack.height(), channels = m_stack.channels();
    if (!useHistory) {
        m_history = m_stack;
        return;
    }
    m_scratch.resize(w, ht, channels);
    const Reprojector& rp = *g.reprojector;
    const bool trust = g.trust && g.trust->active();
    parallelRows(ht, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const float* rowTrust = trust ? g.trust->rowTrust(y) : nullptr;
            for (int x = 0; x < w; ++x) {
                // The output pixel holds the history's weighted sum until the blend.
                float* o = m_scratch.at(x, y);
                std::fill(o, o + channels, 0.0f);
                const float ws = forEachHistoryTap(rp.taps(x, y), [&](int qx, int qy, float wk) {
                    const float* v = m_history.at(qx, qy);
                    for (int c = 0; c < channels; ++c)
                        o[c] += wk * v[c];
                });
                const float* cur = m_stack.at(x, y);
                if (!(ws > 0.0f)) {
                    std::copy(cur, cur + channels, o);
                    continue;
                }
                const float tr = rowTrust ? rowTrust[x] : 1.0f;
                const float a = kAlpha + (1.0f - kAlpha) * (1.0f - tr);
                const float inv = 1.0f / ws;
                for (int c = 0; c < channels; ++c)
                    o[c] = blendHistory(o[c] * inv, cur[c], a);
            }
        }
    });
    std::swap(m_stack, m_scratch);
    m_history = m_stack;
}

void PassTransfer::run(const PassGuides& g, const std::vector<PassBinding>& passes)
{
    const int w = g.beauty.width, ht = g.beauty.height;
    const int n = static_cast<int>(passes.size());
    const int channels = 3 * (n + 1);
    std::vector<std::string> names;
    for (const PassBinding& p : passes)
        names.push_back(p.name);

    // The stack: the rest R = B - sum_i P_i x F_i (what the bound passes do not hold; about 0
    // when every pass is bound and they add up), then every light pass P_i as given (NaN/Inf and
    // negatives as 0, as the method's colour). The guide planes from B', normal and depth.
    m_stack.resize(w, ht, channels);
    m_guide.resize(w, ht * kGuide, 1);
    const std::size_t planeSize = static_cast<std::size_t>(w) * ht;
    parallelRows(ht, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float* s = m_stack.at(x, y);
                const float* b = g.beauty.at(x, y);
                for (int c = 0; c < 3; ++c)
                    s[c] = sanitize(b[c]);
                for (int i = 0; i < n; ++i) {
                    const float* p = passes[i].light.at(x, y);
                    const float* f = passes[i].factor.empty() ? nullptr : passes[i].factor.at(x, y);
                    for (int c = 0; c < 3; ++c) {
                        s[3 * (i + 1) + c] = sanitize(p[c]);
                        s[c] -= sanitize(p[c]) * (f ? sanitize(f[c]) : 1.0f);
                    }
                }
                const float* d = g.denoised.at(x, y);
                float gd[kGuide];
                gd[Luma] = 0.2126f * sanitize(d[0]) + 0.7152f * sanitize(d[1])
                    + 0.0722f * sanitize(d[2]);
                for (int c = 0; c < 3; ++c)
                    gd[Nx + c] = g.normal.empty() ? 0.0f : g.normal.at(x, y)[c];
                const float len = std::sqrt(gd[Nx] * gd[Nx] + gd[Ny] * gd[Ny] + gd[Nz] * gd[Nz]);
                for (int c = 0; c < 3; ++c)
                    gd[Nx + c] = std::isfinite(len) && len > 0.0f ? gd[Nx + c] / len : 0.0f;
                const float z = g.depth.empty() ? 0.0f : g.depth.at(x, y)[0];
                gd[Depth] = std::isfinite(z) ? z : 0.0f;
                gd[LumaScale] = 1.0f / (kLumaSigma * gd[Luma] + 1e-4f);
                gd[DepthScale] = 1.0f / (kDepthSigma * std::fabs(gd[Depth]) + 1e-6f);
                for (int k = 0; k < kGuide; ++k)
                    m_guide.data()[k * planeSize + static_cast<std::size_t>(y) * w + x] = gd[k];
            }
    });
    filterSpatial(g, channels);
    const bool useHistory = g.reprojector && g.reprojector->hasHistory() && names == m_names
        && m_history.width() == w && m_history.height() == ht && m_history.channels() == channels;
    accumulate(g, useHistory);
    m_names = names;

    // T_i* = A(P_i) x F_i, D = sum_i T_i* + A(R), g = B' / D; the pass is A(P_i) x g.
    parallelRows(ht, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* s = m_stack.at(x, y);
                const float* d = g.denoised.at(x, y);
                float denom[3] = { s[0], s[1], s[2] };
                for (int i = 0; i < n; ++i) {
                    const float* f = passes[i].factor.empty() ? nullptr : passes[i].factor.at(x, y);
                    for (int c = 0; c < 3; ++c)
                        denom[c] += s[3 * (i + 1) + c] * (f ? sanitize(f[c]) : 1.0f);
                }
                float gain[3];
                for (int c = 0; c < 3; ++c)
                    gain[c] = denom[c] > kBlack ? sanitize(d[c]) / denom[c] : 1.0f;
                // Where the filtered passes are black but B' is not (the method carried light into
                // a neighbourhood where no sample found any), B' goes to the first bound pass
                // whose factor there is at least kFallbackFactor (or that has none).
                bool placed[3] = { false, false, false };
                for (int i = 0; i < n; ++i) {
                    float* o = passes[i].output.atMutable(x, y);
                    const float* f = passes[i].factor.empty() ? nullptr : passes[i].factor.at(x, y);
                    for (int c = 0; c < 3; ++c) {
                        o[c] = s[3 * (i + 1) + c] * gain[c];
                        const float fc = f ? sanitize(f[c]) : 1.0f;
                        if (!(denom[c] > kBlack) && !placed[c] && fc >= kFallbackFactor) {
                            o[c] += sanitize(d[c]) / fc;
                            placed[c] = true;
                        }
                    }
                    if (passes[i].output.channels >= 4)
                        o[3] = 1.0f;
                }
            }
    });
}

} // namespace afn
