// SPDX-License-Identifier: Apache-2.0
// The aux prefilter (stages/aux_prefilter.h: the rule and its reasoning; stages/aux_noise.h: the
// speckle test) on the CUDA engine, one pixel at a time, in the CPU's order of operations so that
// the prefiltered albedo, normal and depth are the CPU's bit for bit (compiled with --fmad=false,
// aux_prefilter.cu). The 5x5 box means are evaluated per pixel as the CPU's separable ones: each
// row's sum over the window's columns divided by their count, summed over the rows, divided by
// theirs. Kernels in order (aux_prefilter.cu): begin, flags (speckle flags and discontinuity
// shares, counted), decide (the auto decision on the first frame of a history), geometry
// (normal, depth), albedo (the demodulation factor through the history taps).
#pragma once

#include "cuda/prepare_block.h"
#include "cuda/temporal_pixel.h"

#include <cstdint>

namespace afn::cuda {

// stages/aux_noise.h and stages/aux_prefilter.h (afn_pipeline.cpp checks they are the same).
constexpr float kAuxAlbedoThresholdDevice = 0.1f;
constexpr float kAuxNormalThresholdDevice = 0.3f;
constexpr float kAuxDepthThresholdDevice = 0.05f;
constexpr float kAuxAlbedoLevelFloorDevice = 0.1f;
constexpr float kAuxDepthSkyDevice = 1e9f;
constexpr double kAuxNoisyShareDevice = 0.005;
constexpr int kAuxTrustedSppDevice = 16;
constexpr float kAuxUnreliableShareDevice = 0.16f;
constexpr float kAuxDenseLowDevice = 0.3f;
constexpr float kAuxDenseHighDevice = 0.45f;
constexpr float kAuxAlbedoAlphaMinDevice = 0.1f;
constexpr float kAuxNoisyAlbedoFloorDevice = 1.0f / 32.0f;
constexpr float kAuxGrainLimitDevice = 0.1f;
constexpr int kAuxHistoryStride = 5; ///< floats per pixel of the aux history (at most 5 used)

/// AuxSettings::Mode as FrameConstants::auxMode holds it.
enum AuxModeDevice { kAuxAuto = 0, kAuxClean = 1, kAuxNoisy = 2 };
/// The buffers the speckle test reads (AuxKind).
enum AuxKindDevice { kAuxAlbedo = 0, kAuxNormal = 1, kAuxDepth = 2 };

/// What the aux prefilter keeps from frame to frame on the device (AuxPrefilter's members).
struct AuxState {
    unsigned counts[3]; ///< speckle pixels of this frame's albedo, normal, depth
    int decided; ///< the auto decision is made for this history
    int noisy; ///< prefiltering in effect
    int grainLimited; ///< from 16 spp: the albedo's grain limited over time
    int hasHistory; ///< the aux history holds the previous frame
    int useHistory; ///< this frame gathers it
};

/// Buffers of the aux prefilter (frame size, interleaved floats; absent inputs null).
struct AuxBuffers {
    int width = 0;
    int height = 0;
    const float* albedo = nullptr; ///< as given, 3 ch
    const float* normal = nullptr; ///< as given, 3 ch
    const float* depth = nullptr; ///< as given, 1 ch
    float* flags[3] = { nullptr, nullptr, nullptr }; ///< speckle flags (0 or 1) per kind
    float* edges[2] = { nullptr, nullptr }; ///< discontinuity shares: albedo, normal
    float* albedoOut = nullptr; ///< the demodulation albedo d (3 ch)
    float* normalOut = nullptr; ///< the normal after the prefilter (3 ch)
    float* depthOut = nullptr; ///< the depth after the prefilter (1 ch)
    const float* prevHistory = nullptr; ///< kAuxHistoryStride floats per pixel
    float* history = nullptr;
    AuxState* state = nullptr;
};

namespace aux {

AFN_HD bool hasSurface(float z)
{
    return isFiniteFloat(z) && fabsf(z) < kAuxDepthSkyDevice;
}

AFN_HD float threshold(int kind)
{
    return kind == kAuxAlbedo ? kAuxAlbedoThresholdDevice
        : kind == kAuxNormal  ? kAuxNormalThresholdDevice
                              : kAuxDepthThresholdDevice;
}

AFN_HD int channels(int kind)
{
    return kind == kAuxDepth ? 1 : 3;
}

/// dist(p, q) of the kind (stages/aux_noise.cpp distance()); +inf where q has no surface (depth).
AFN_HD float distance(int kind, const float* p, const float* q)
{
    if (kind == kAuxAlbedo) {
        float d = fabsf(p[0] - q[0]); // std::max({ ... }): the first largest
        d = d < fabsf(p[1] - q[1]) ? fabsf(p[1] - q[1]) : d;
        d = d < fabsf(p[2] - q[2]) ? fabsf(p[2] - q[2]) : d;
        float level = p[0];
        const float others[6] = { p[1], p[2], q[0], q[1], q[2], kAuxAlbedoLevelFloorDevice };
        for (float o : others)
            level = level < o ? o : level;
        return d / level;
    }
    if (kind == kAuxNormal) {
        const float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
        return sqrtf(dx * dx + dy * dy + dz * dz);
    }
    if (!hasSurface(q[0]))
        return bitsFloat(0x7f800000u);
    const float ap = fabsf(p[0]), aq = fabsf(q[0]);
    const float lo = aq < ap ? aq : ap; // std::min
    return fabsf(p[0] - q[0]) / (lo < 1e-6f ? 1e-6f : lo);
}

/// Whether pixel (x, y) of `img` is speckle (stages/aux_noise.cpp isSpeckle(), flagRows()).
AFN_HD bool speckle(int kind, const float* img, int w, int h, int x, int y)
{
    const int c = channels(kind);
    const float* p = img + (static_cast<std::size_t>(y) * w + x) * c;
    if (kind == kAuxDepth && !hasSurface(p[0]))
        return false;
    const int dxs[8] = { -1, 1, 0, 0, -1, 1, -1, 1 };
    const int dys[8] = { 0, 0, -1, 1, -1, -1, 1, 1 };
    const float t = threshold(kind);
    float best = bitsFloat(0x7f800000u);
    for (int k = 0; k < 8; ++k) {
        const int qx = x + dxs[k], qy = y + dys[k];
        if (qx < 0 || qy < 0 || qx >= w || qy >= h)
            continue;
        const float d = distance(kind, p, img + (static_cast<std::size_t>(qy) * w + qx) * c);
        if (d <= t)
            return false;
        best = d < best ? d : best; // std::min(best, d): NaN keeps best
    }
    return isFiniteFloat(best);
}

/// Share of pixel (x, y)'s 4 edge neighbours farther than the threshold (discontinuityRows()).
AFN_HD float discontinuity(int kind, const float* img, int w, int h, int x, int y)
{
    const int dxs[4] = { -1, 1, 0, 0 };
    const int dys[4] = { 0, 0, -1, 1 };
    const float* p = img + (static_cast<std::size_t>(y) * w + x) * 3;
    const float t = threshold(kind);
    int n = 0, far = 0;
    for (int k = 0; k < 4; ++k) {
        const int qx = x + dxs[k], qy = y + dys[k];
        if (qx < 0 || qy < 0 || qx >= w || qy >= h)
            continue;
        ++n;
        far += distance(kind, p, img + (static_cast<std::size_t>(qy) * w + qx) * 3) > t ? 1 : 0;
    }
    return n > 0 ? static_cast<float>(far) / static_cast<float>(n) : 0.0f;
}

/// Mean over the 5x5 window clipped to the frame of C channels, `load(qx, qy, v)` giving pixel
/// (qx, qy) (aux_prefilter.cpp boxMean(): the same sums in the same order).
template <int C, typename Load>
AFN_HD void boxMean(int w, int h, int x, int y, Load load, float* out)
{
    const int xa = x - 2 < 0 ? 0 : x - 2, xb = x + 2 > w - 1 ? w - 1 : x + 2;
    const int ya = y - 2 < 0 ? 0 : y - 2, yb = y + 2 > h - 1 ? h - 1 : y + 2;
    float acc[C];
    for (int k = 0; k < C; ++k)
        acc[k] = 0.0f;
    for (int qy = ya; qy <= yb; ++qy) {
        float sum[C];
        for (int k = 0; k < C; ++k)
            sum[k] = 0.0f;
        for (int qx = xa; qx <= xb; ++qx) {
            float v[C];
            load(qx, qy, v);
            for (int k = 0; k < C; ++k)
                sum[k] += v[k];
        }
        for (int k = 0; k < C; ++k)
            acc[k] += sum[k] / static_cast<float>(xb - xa + 1);
    }
    for (int k = 0; k < C; ++k)
        out[k] = acc[k] / static_cast<float>(yb - ya + 1);
}

/// Mean of a 1- or 3-channel plane.
template <int C> AFN_HD void planeMean(const float* plane, int w, int h, int x, int y, float* out)
{
    boxMean<C>(
        w, h, x, y,
        [&](int qx, int qy, float* v) {
            const float* p = plane + (static_cast<std::size_t>(qy) * w + qx) * C;
            for (int k = 0; k < C; ++k)
                v[k] = p[k];
        },
        out);
}

/// The speckle share of (x, y)'s window, raised where its discontinuities say dense speckle
/// (aux_prefilter.cpp windowShare()); `edges` null: the plain share (depth).
AFN_HD float windowShare(const float* flags, const float* edges, int w, int h, int x, int y)
{
    float share, dense;
    planeMean<1>(flags, w, h, x, y, &share);
    if (!edges)
        return share;
    planeMean<1>(edges, w, h, x, y, &dense);
    float ramp = (dense - kAuxDenseLowDevice) / (kAuxDenseHighDevice - kAuxDenseLowDevice);
    ramp = ramp < 0.0f ? 0.0f : (1.0f < ramp ? 1.0f : ramp); // std::clamp
    const float raised = kAuxUnreliableShareDevice * ramp;
    return share < raised ? raised : share;
}

AFN_HD float reliability(float share)
{
    const float r = 1.0f - share / kAuxUnreliableShareDevice;
    return r < 0.0f ? 0.0f : (1.0f < r ? 1.0f : r);
}

} // namespace aux

/// Flags and discontinuity shares of pixel (x, y) for the present buffers; returns which kinds
/// are speckle there (bit k: kind k).
AFN_HD unsigned auxFlagsPixel(const AuxBuffers& b, int x, int y)
{
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    const float* images[3] = { b.albedo, b.normal, b.depth };
    unsigned speckled = 0;
    for (int kind = 0; kind < 3; ++kind) {
        if (!images[kind])
            continue;
        const bool s = aux::speckle(kind, images[kind], b.width, b.height, x, y);
        b.flags[kind][i] = s ? 1.0f : 0.0f;
        speckled |= s ? 1u << kind : 0u;
        if (kind < 2)
            b.edges[kind][i] = aux::discontinuity(kind, images[kind], b.width, b.height, x, y);
    }
    return speckled;
}

/// The auto decision and the history flags of a frame (AuxPrefilter::prepare(), finish()).
AFN_HD void auxDecide(const AuxBuffers& b, const FrameConstants& f)
{
    AuxState& s = *b.state;
    if (!s.decided) {
        const double pixels = static_cast<double>(b.width) * b.height;
        const double albedo = b.albedo ? s.counts[0] / pixels : -1.0;
        const double normal = b.normal ? s.counts[1] / pixels : -1.0;
        const bool speckled = (albedo < normal ? normal : albedo) > kAuxNoisyShareDevice;
        s.noisy = f.auxMode == kAuxNoisy
            || (f.auxMode == kAuxAuto && f.spp < kAuxTrustedSppDevice && speckled);
        s.grainLimited = f.auxMode == kAuxAuto && f.spp >= kAuxTrustedSppDevice && speckled;
        s.decided = 1;
    }
    s.useHistory = s.hasHistory && f.hasHistory;
    s.hasHistory = (s.noisy || s.grainLimited) && b.albedo && !f.colorDemodulated;
}

/// The normal and depth of pixel (x, y) after the prefilter (as given unless noisy).
AFN_HD void auxGeometryPixel(const AuxBuffers& b, int x, int y)
{
    using namespace aux;
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    const bool noisy = b.state->noisy != 0;
    if (b.normal) {
        const float* n = b.normal + 3 * i;
        float* o = b.normalOut + 3 * i;
        for (int k = 0; k < 3; ++k)
            o[k] = n[k];
        const float r = noisy ? reliability(windowShare(
                            b.flags[kAuxNormal], b.edges[kAuxNormal], b.width, b.height, x, y))
                              : 1.0f;
        if (r < 1.0f) {
            float m[3];
            planeMean<3>(b.normal, b.width, b.height, x, y, m);
            float v[3], len2 = 0.0f;
            for (int k = 0; k < 3; ++k) {
                v[k] = r * n[k] + (1.0f - r) * m[k];
                len2 += v[k] * v[k];
            }
            if (len2 > 1e-12f)
                for (int k = 0; k < 3; ++k)
                    o[k] = v[k] / sqrtf(len2);
        }
    }
    if (b.depth) {
        const float z = b.depth[i];
        b.depthOut[i] = z;
        if (!noisy || !hasSurface(z))
            return;
        const float r
            = reliability(windowShare(b.flags[kAuxDepth], nullptr, b.width, b.height, x, y));
        if (r >= 1.0f)
            return;
        float m[2]; // mean of (z, 1) over pixels with a surface
        boxMean<2>(
            b.width, b.height, x, y,
            [&](int qx, int qy, float* v) {
                const float q = b.depth[static_cast<std::size_t>(qy) * b.width + qx];
                const bool ok = hasSurface(q);
                v[0] = ok ? q : 0.0f;
                v[1] = ok ? 1.0f : 0.0f;
            },
            m);
        if (m[1] > 0.0f)
            b.depthOut[i] = r * z + (1.0f - r) * (m[0] / m[1]);
    }
}

/// One step of the aux history at (x, y) over N channels plus the length (aux_prefilter.cpp
/// accumulateStep()): `taps` from the prefiltered geometry, or none.
template <int N>
AFN_HD void auxAccumulate(const AuxBuffers& b, const HistoryTaps* taps, const float* cur, float* o)
{
    float prev[N + 1];
    for (int c = 0; c <= N; ++c)
        prev[c] = 0.0f;
    float ws = 0.0f;
    if (taps) {
        for (int k = 0; k < 4; ++k) {
            if (!(taps->w[k] > 0.0f))
                continue;
            const float* v = b.prevHistory + taps->index(b.width, k) * kAuxHistoryStride;
            for (int c = 0; c <= N; ++c)
                prev[c] += taps->w[k] * v[c];
            ws += taps->w[k];
        }
        if (ws > 0.0f)
            for (int c = 0; c <= N; ++c)
                prev[c] /= ws;
    }
    if (ws > 0.0f) {
        const float len = minOf(prev[N] + 1.0f, kMaxHistoryLengthDevice);
        const float alpha = maxOf(1.0f / len, kAuxAlbedoAlphaMinDevice);
        for (int k = 0; k < N; ++k)
            o[k] = prev[k] + alpha * (cur[k] - prev[k]);
        o[N] = len;
    } else {
        for (int k = 0; k < N; ++k)
            o[k] = cur[k];
        o[N] = 1.0f;
    }
}

/// The demodulation albedo of pixel (x, y) (AuxPrefilter::finish(), limitGrain()): `t` are the
/// frame's temporal buffers with the prefiltered geometry (for the history taps).
AFN_HD void auxAlbedoPixel(
    const AuxBuffers& b, const TemporalBuffers& t, const FrameConstants& f, int x, int y)
{
    using namespace aux;
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    const float* a = b.albedo + 3 * i;
    float* d = b.albedoOut + 3 * i;
    for (int k = 0; k < 3; ++k)
        d[k] = a[k];
    const AuxState& s = *b.state;
    if (f.colorDemodulated || !(s.noisy || s.grainLimited))
        return;
    HistoryTaps taps;
    const bool gather = s.useHistory && historyTaps(t, f, x, y, taps);
    float* o = b.history + i * kAuxHistoryStride;
    if (s.grainLimited) {
        auxAccumulate<3>(b, gather ? &taps : nullptr, a, o);
        for (int k = 0; k < 3; ++k) { // std::clamp(o, a (1 - g), a (1 + g))
            const float lo = a[k] * (1.0f - kAuxGrainLimitDevice);
            const float hi = a[k] * (1.0f + kAuxGrainLimitDevice);
            const float v = o[k] < lo ? lo : (hi < o[k] ? hi : o[k]);
            d[k] = o[k] = v;
        }
        return;
    }
    float cur[4];
    planeMean<3>(b.albedo, b.width, b.height, x, y, cur);
    cur[3] = windowShare(b.flags[kAuxAlbedo], b.edges[kAuxAlbedo], b.width, b.height, x, y);
    auxAccumulate<4>(b, gather ? &taps : nullptr, cur, o);
    const float r = b.flags[kAuxAlbedo][i] > 0.0f ? 0.0f : reliability(o[3]);
    if (r >= 1.0f)
        return;
    const float floor = (1.0f - r) * kAuxNoisyAlbedoFloorDevice;
    for (int k = 0; k < 3; ++k) {
        const float v = r * a[k] + (1.0f - r) * o[k];
        d[k] = v < floor ? floor : v; // std::max(v, floor)
    }
}

} // namespace afn::cuda
