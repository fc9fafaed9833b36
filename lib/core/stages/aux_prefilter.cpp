// SPDX-License-Identifier: Apache-2.0
// Prefiltering of possibly-noisy auxiliary buffers (see stages/aux_prefilter.h).
#include "stages/aux_prefilter.h"

#include "base/parallel.h"
#include "stages/temporal_accumulation.h"

#include <algorithm>
#include <cmath>

namespace afn {

const ParamBinding<AuxSettings>& auxBinding()
{
    using M = AuxSettings::Mode;
    static const ParamBinding<AuxSettings> binding
        = ParamBinding<AuxSettings>()
              .add(&AuxSettings::aux, AFN_PARAM_AUX,
                  { { "auto", M::Auto }, { "clean", M::Clean }, { "noisy", M::Noisy } },
                  "Auxiliary buffers",
                  "albedo/normal/depth quality: clean (first-hit AOVs, used as given), noisy "
                  "(AOVs that follow specular bounces or carry DOF/motion-blur noise: "
                  "prefiltered, demodulation blended towards a smooth albedo where unreliable) "
                  "or auto (below 16 spp decided on the first frame from the share of speckle "
                  "pixels, reported as stats.auxNoisy; from 16 spp the buffers as given, with "
                  "the albedo's grain limited over time where speckle is found, reported as "
                  "stats.auxGrainLimited)")
              .add(&AuxSettings::spp, AFN_PARAM_SPP, 0, 1 << 20, "Samples per pixel",
                  "samples per pixel of the colour input (0 = unknown, taken as low): "
                  "with aux=auto the auxiliary buffers are used as given from 16 spp on, "
                  "restore=auto gives back the frame's detail from 16 spp on, "
                  "and the afn method picks the model trained nearest this count; "
                  "afntool reads it from the file (Blender: cycles.<layer>.samples) "
                  "unless given");
    return binding;
}

namespace {

constexpr int kRadius = 2; ///< 5x5 windows

/// Horizontal pass of boxMean for C channels: per pixel and channel the sum from 0 over the
/// window's columns in ascending order, in a register (the earlier code summed into the output
/// image itself, which the compiler had to store and reload per tap: the same order, the same
/// bits, several times slower).
template <int C> void boxRows(const Image& src, Image& dst, int y0, int y1)
{
    const int w = src.width();
    for (int y = y0; y < y1; ++y) {
        const float* s = src.at(0, y);
        float* d = dst.at(0, y);
        for (int x = 0; x < w; ++x) {
            const int xa = std::max(x - kRadius, 0), xb = std::min(x + kRadius, w - 1);
            float sum[C] = {};
            for (int q = xa; q <= xb; ++q)
                for (int k = 0; k < C; ++k)
                    sum[k] += s[q * C + k];
            for (int k = 0; k < C; ++k)
                d[x * C + k] = sum[k] / static_cast<float>(xb - xa + 1);
        }
    }
}

/// Mean over the (2r+1)^2 window clipped to the image, per channel (separable box sums; 1 to 3
/// channels).
void boxMean(const Image& src, Image& tmp, Image& out)
{
    const int w = src.width(), h = src.height(), c = src.channels();
    tmp.resize(w, h, c);
    out.resize(w, h, c);
    parallelRows(h, [&](int y0, int y1) {
        if (c == 1)
            boxRows<1>(src, tmp, y0, y1);
        else if (c == 2)
            boxRows<2>(src, tmp, y0, y1);
        else
            boxRows<3>(src, tmp, y0, y1);
    });
    // Vertical: each value the sum from 0 over the window's rows in ascending order, row by row
    // over whole rows (contiguous, so vectorised), then divided.
    const int n = w * c;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            float* o = out.at(0, y);
            const int ya = std::max(y - kRadius, 0), yb = std::min(y + kRadius, h - 1);
            for (int i = 0; i < n; ++i)
                o[i] = 0.0f;
            for (int q = ya; q <= yb; ++q) {
                const float* t = tmp.at(0, q);
                for (int i = 0; i < n; ++i)
                    o[i] += t[i];
            }
            const float count = static_cast<float>(yb - ya + 1);
            for (int i = 0; i < n; ++i)
                o[i] /= count;
        }
    });
}

/// The speckle share of each pixel's 5x5 window of `img` (flags: its speckle flags), raised where
/// the window's differing adjacent pairs say dense speckle (aux_prefilter.h, step 2), into `share`.
void windowShare(const Image& img, AuxKind kind, const Image& flags, Image& tmp, Image& edges,
    Image& dense, Image& share)
{
    boxMean(flags, tmp, share);
    discontinuityShares(img.view(), kind, edges);
    boxMean(edges, tmp, dense);
    parallelRows(img.height(), [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < img.width(); ++x) {
                const float ramp = std::clamp(
                    (dense(x, y, 0) - kAuxDenseLow) / (kAuxDenseHigh - kAuxDenseLow), 0.0f, 1.0f);
                share(x, y, 0) = std::max(share(x, y, 0), kAuxUnreliableShare * ramp);
            }
    });
}

inline float reliability(float share)
{
    return std::clamp(1.0f - share / kAuxUnreliableShare, 0.0f, 1.0f);
}

/// One step of the aux history's temporal accumulation at (x, y): o[0..N) = prev + alpha (cur -
/// prev) with alpha = max(1 / len, kAuxAlbedoAlphaMin) and o[N] = len = min(prev length + 1,
/// kMaxHistoryLength), prev gathered from `hist` (N + 1 channels) through the taps; without taps
/// or an accepted tap, o = cur and length 1.
template <int N>
void accumulateStep(
    const Reprojector* taps, int x, int y, const Image& hist, const float* cur, float* o)
{
    float prev[N + 1];
    const float ws = taps ? gatherHistory<N + 1>(taps->taps(x, y), hist, prev) : 0.0f;
    if (ws > 0.0f) {
        const float len = std::min(prev[N] + 1.0f, kMaxHistoryLength);
        const float alpha = std::max(1.0f / len, kAuxAlbedoAlphaMin);
        for (int k = 0; k < N; ++k)
            o[k] = prev[k] + alpha * (cur[k] - prev[k]);
        o[N] = len;
    } else {
        for (int k = 0; k < N; ++k)
            o[k] = cur[k];
        o[N] = 1.0f;
    }
}

inline bool hasSurface(float z)
{
    return std::isfinite(z) && std::fabs(z) < kAuxDepthSky;
}

} // namespace

void AuxPrefilter::reset()
{
    m_decided = false;
    m_hasHistory = false;
}

namespace {

/// Share of speckle pixels of `img`; -1 when it is empty (absent input).
double measuredShare(const ImageView& img, AuxKind kind)
{
    return img.empty() ? -1.0 : speckleShare(img, kind);
}

} // namespace

void AuxPrefilter::measureShares(
    const ImageView& albedo, const ImageView& normal, const ImageView& depth) const
{
    if (!m_sharesPending)
        return;
    m_report.albedoSpeckle = measuredShare(albedo, AuxKind::Albedo);
    m_report.normalSpeckle = measuredShare(normal, AuxKind::Normal);
    m_report.depthSpeckle = measuredShare(depth, AuxKind::Depth);
    m_sharesPending = false;
}

void AuxPrefilter::prepare(Frame& f)
{
    m_sharesPending = false;
    if (m_decided && !m_report.noisy && !m_report.grainLimited) {
        // A history decided clean leaves every buffer as given and reads no flags: its shares
        // are only reported, so they are measured when asked for (measureShares): a full pass
        // over albedo, normal and depth saved on every frame (about a tenth of ta's time).
        m_sharesPending = true;
        return;
    }
    const std::int64_t pixels = static_cast<std::int64_t>(f.width) * f.height;
    // The flags themselves are needed only where this history may be (or is) prefiltered; a
    // history decided grain-limited (or aux=clean on its first frame) only reports the shares:
    // counted, not stored.
    const bool keepFlags = m_decided ? m_report.noisy : m_settings.aux != AuxSettings::Mode::Clean;
    auto share = [&](const Image& img, AuxKind kind, Image& flags) {
        if (!keepFlags || img.empty())
            return measuredShare(img.view(), kind);
        return static_cast<double>(speckleFlags(img.view(), kind, flags)) / pixels;
    };
    m_report.albedoSpeckle = share(f.albedo, AuxKind::Albedo, m_albedoFlags);
    m_report.normalSpeckle = share(f.normal, AuxKind::Normal, m_normalFlags);
    m_report.depthSpeckle = share(f.depth, AuxKind::Depth, m_depthFlags);

    if (!m_decided) {
        using M = AuxSettings::Mode;
        const bool speckled
            = std::max(m_report.albedoSpeckle, m_report.normalSpeckle) > kAuxNoisyShare;
        m_report.noisy = m_settings.aux == M::Noisy
            || (m_settings.aux == M::Auto && m_settings.spp < kAuxTrustedSpp && speckled);
        m_report.grainLimited
            = m_settings.aux == M::Auto && m_settings.spp >= kAuxTrustedSpp && speckled;
        m_decided = true;
    }
    if (!m_report.noisy) {
        // A clean history never reads flags or prefilter buffers again: free them (frame-size
        // buffers are kept only while in use), so they do not add to every later frame.
        for (Image* img : { &m_albedoFlags, &m_normalFlags, &m_depthFlags, &m_share, &m_mean,
                 &m_tmp, &m_depthValid, &m_edges, &m_dense })
            *img = Image();
        if (!m_report.grainLimited)
            m_hist = m_prevHist = Image();
        return;
    }

    if (f.hasNormal()) {
        windowShare(f.normal, AuxKind::Normal, m_normalFlags, m_tmp, m_edges, m_dense, m_share);
        boxMean(f.normal, m_tmp, m_mean);
        parallelRows(f.height, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < f.width; ++x) {
                    const float r = reliability(m_share(x, y, 0));
                    if (r >= 1.0f)
                        continue;
                    float* n = f.normal.at(x, y);
                    const float* m = m_mean.at(x, y);
                    float v[3], len2 = 0.0f;
                    for (int k = 0; k < 3; ++k) {
                        v[k] = r * n[k] + (1.0f - r) * m[k];
                        len2 += v[k] * v[k];
                    }
                    if (len2 > 1e-12f)
                        for (int k = 0; k < 3; ++k)
                            n[k] = v[k] / std::sqrt(len2);
                }
        });
    }
    if (f.hasDepth()) {
        // Mean over pixels with a surface: channels (z * valid, valid).
        Image& zv = m_depthValid;
        zv.resize(f.width, f.height, 2);
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const float z = f.depth(x, y, 0);
                const bool ok = hasSurface(z);
                zv(x, y, 0) = ok ? z : 0.0f;
                zv(x, y, 1) = ok ? 1.0f : 0.0f;
            }
        boxMean(m_depthFlags, m_tmp, m_share);
        boxMean(zv, m_tmp, m_mean);
        parallelRows(f.height, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < f.width; ++x) {
                    const float r = reliability(m_share(x, y, 0));
                    float& z = f.depth(x, y, 0);
                    if (r >= 1.0f || !hasSurface(z) || !(m_mean(x, y, 1) > 0.0f))
                        continue;
                    z = r * z + (1.0f - r) * (m_mean(x, y, 0) / m_mean(x, y, 1));
                }
        });
    }
}

void AuxPrefilter::finish(Frame& f, const Reprojector* taps)
{
    if (m_report.grainLimited && f.hasAlbedo() && !f.colorDemodulated) {
        limitGrain(f, taps);
        return;
    }
    if (!m_report.noisy || !f.hasAlbedo() || f.colorDemodulated) {
        m_hasHistory = false;
        return;
    }
    const int w = f.width, h = f.height;
    // Current (smoothed albedo, flag share) per pixel, then its temporal accumulation.
    windowShare(f.albedo, AuxKind::Albedo, m_albedoFlags, m_tmp, m_edges, m_dense, m_share);
    boxMean(f.albedo, m_tmp, m_mean);
    std::swap(m_hist, m_prevHist);
    m_hist.resize(w, h, 5);
    const bool history = m_hasHistory && taps && taps->hasHistory() && m_prevHist.width() == w
        && m_prevHist.height() == h;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float cur[4]
                    = { m_mean(x, y, 0), m_mean(x, y, 1), m_mean(x, y, 2), m_share(x, y, 0) };
                float* o = m_hist.at(x, y);
                accumulateStep<4>(history ? taps : nullptr, x, y, m_prevHist, cur, o);
                // A speckle pixel itself (it differs from all 8 neighbours) takes the smooth
                // estimate whatever its window's share (aux_prefilter.h, step 4).
                const float r = m_albedoFlags(x, y, 0) > 0.0f ? 0.0f : reliability(o[3]);
                if (r >= 1.0f)
                    continue; // reliable: the albedo stays exactly as given
                float* a = f.albedo.at(x, y);
                const float floor = (1.0f - r) * kAuxNoisyAlbedoFloor;
                for (int k = 0; k < 3; ++k)
                    a[k] = std::max(r * a[k] + (1.0f - r) * o[k], floor);
            }
    });
    m_hasHistory = true;
}

// From kAuxTrustedSpp (aux=auto, speckle found): the albedo as given, except that its grain (the
// sub-pixel texture sampling noise a 16-spp albedo still carries) is averaged over time: the
// temporal accumulation of the per-pixel albedo (the colour's taps and history rule, alpha >=
// kAuxAlbedoAlphaMin), clamped to within kAuxGrainLimit of this frame's value, so texture,
// edges and changes larger than that follow the given albedo at once.
void AuxPrefilter::limitGrain(Frame& f, const Reprojector* taps)
{
    const int w = f.width, h = f.height;
    constexpr float kGrain = kAuxGrainLimit;
    std::swap(m_hist, m_prevHist);
    m_hist.resize(w, h, 4);
    const bool history = m_hasHistory && taps && taps->hasHistory() && m_prevHist.width() == w
        && m_prevHist.height() == h && m_prevHist.channels() == 4;
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float* a = f.albedo.at(x, y);
                float* o = m_hist.at(x, y);
                accumulateStep<3>(history ? taps : nullptr, x, y, m_prevHist, a, o);
                for (int k = 0; k < 3; ++k) // no history: o = a, inside the band already
                    a[k] = o[k] = std::clamp(o[k], a[k] * (1.0f - kGrain), a[k] * (1.0f + kGrain));
            }
    });
    m_hasHistory = true;
}

} // namespace afn
