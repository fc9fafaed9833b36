// SPDX-License-Identifier: Apache-2.0
#include "stages/pass_transfer.h"

#include "base/parallel.h"

#include <algorithm>
#include <cmath>

namespace afn {
namespace {

/// Edge stops of the shared filter (see pass_transfer.h): relative luminance difference of the
/// denoised beauty, normal cosine power, relative depth difference (per a-trous step).
constexpr float kLumaSigma = 0.2f;
constexpr float kNormalPower = 16.0f;
constexpr float kDepthSigma = 0.02f;
/// The guide channels: luminance, normal xyz, depth.
constexpr int kGuide = 5;
/// A filtered beauty at or below this is black: the gain is 1 there.
constexpr float kBlack = 1e-12f;

/// NaN/Inf and negatives as 0, as the methods read their colour.
float sanitize(float v)
{
    return std::isfinite(v) && v > 0.0f ? v : 0.0f;
}

float guideWeight(const float* gp, const float* gq, bool normals, bool depth, int step)
{
    const float lp = gp[0], lq = gq[0];
    float e = std::fabs(lp - lq) / (kLumaSigma * std::max(lp, lq) + 1e-4f);
    if (depth) {
        const float zp = gp[4], zq = gq[4];
        e += std::fabs(zp - zq)
            / (kDepthSigma * step * std::max(std::fabs(zp), std::fabs(zq)) + 1e-6f);
    }
    float w = std::exp(-e);
    if (normals) {
        const float d = std::max(0.0f, gp[1] * gq[1] + gp[2] * gq[2] + gp[3] * gq[3]);
        w *= std::pow(d, kNormalPower);
    }
    return w;
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
    for (int level = 0; level < kLevels; ++level) {
        const int step = 1 << level;
        parallelRows(ht, [&](int y0, int y1) {
            std::vector<float> acc(static_cast<std::size_t>(channels));
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < w; ++x) {
                    const float* gp = m_guide.at(x, y);
                    std::fill(acc.begin(), acc.end(), 0.0f);
                    float wsum = 0.0f;
                    for (int j = -2; j <= 2; ++j) {
                        const int qy = y + j * step;
                        if (qy < 0 || qy >= ht)
                            continue;
                        for (int i = -2; i <= 2; ++i) {
                            const int qx = x + i * step;
                            if (qx < 0 || qx >= w)
                                continue;
                            const float wq = h[i + 2] * h[j + 2]
                                * (i == 0 && j == 0 ? 1.0f
                                                    : guideWeight(gp, m_guide.at(qx, qy), normals,
                                                        depth, step));
                            if (!(wq > 0.0f))
                                continue;
                            const float* v = src->at(qx, qy);
                            for (int c = 0; c < channels; ++c)
                                acc[c] += wq * v[c];
                            wsum += wq;
                        }
                    }
                    float* o = dst->at(x, y);
                    const float inv = 1.0f / wsum; // the centre tap is always in: wsum > 0
                    for (int c = 0; c < channels; ++c)
                        o[c] = acc[c] * inv;
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
        std::vector<float> prev(static_cast<std::size_t>(channels));
        for (int y = y0; y < y1; ++y) {
            const float* rowTrust = trust ? g.trust->rowTrust(y) : nullptr;
            for (int x = 0; x < w; ++x) {
                const PixelTaps t = rp.taps(x, y);
                std::fill(prev.begin(), prev.end(), 0.0f);
                float ws = 0.0f;
                auto add = [&](int qx, int qy, float wk) {
                    const float* v = m_history.at(qx, qy);
                    for (int c = 0; c < channels; ++c)
                        prev[c] += wk * v[c];
                    ws += wk;
                };
                if (!t.box) {
                    for (int k = 0; k < 4; ++k)
                        if ((t.mask & (1u << k)) && t.w[k] > 0.0f)
                            add(t.x0 + (k & 1), t.y0 + (k >> 1), t.w[k]);
                } else {
                    for (int k = 0; k < 9; ++k)
                        if (t.mask & (1u << k))
                            add(t.x0 + k % 3 - 1, t.y0 + k / 3 - 1, 1.0f);
                }
                const float* cur = m_stack.at(x, y);
                float* o = m_scratch.at(x, y);
                if (!(ws > 0.0f)) {
                    std::copy(cur, cur + channels, o);
                    continue;
                }
                const float tr = rowTrust ? rowTrust[x] : 1.0f;
                const float a = kAlpha + (1.0f - kAlpha) * (1.0f - tr);
                const float inv = 1.0f / ws;
                for (int c = 0; c < channels; ++c)
                    o[c] = blendHistory(prev[c] * inv, cur[c], a);
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
    // negatives as 0, as the method's colour).
    m_stack.resize(w, ht, channels);
    m_guide.resize(w, ht, kGuide);
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
                float* gd = m_guide.at(x, y);
                gd[0] = 0.2126f * sanitize(d[0]) + 0.7152f * sanitize(d[1])
                    + 0.0722f * sanitize(d[2]);
                for (int c = 0; c < 3; ++c)
                    gd[1 + c] = g.normal.empty() ? 0.0f : g.normal.at(x, y)[c];
                const float len = std::sqrt(gd[1] * gd[1] + gd[2] * gd[2] + gd[3] * gd[3]);
                for (int c = 0; c < 3; ++c)
                    gd[1 + c] = std::isfinite(len) && len > 0.0f ? gd[1 + c] / len : 0.0f;
                const float z = g.depth.empty() ? 0.0f : g.depth.at(x, y)[0];
                gd[4] = std::isfinite(z) ? z : 0.0f;
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
                for (int i = 0; i < n; ++i) {
                    float* o = passes[i].output.atMutable(x, y);
                    for (int c = 0; c < 3; ++c)
                        o[c] = s[3 * (i + 1) + c] * gain[c];
                    if (passes[i].output.channels >= 4)
                        o[3] = 1.0f;
                }
            }
    });
}

} // namespace afn
