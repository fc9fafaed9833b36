// SPDX-License-Identifier: Apache-2.0
// One pixel of the CUDA engine's first stage: demodulation (stages/demodulate.cpp), reprojection
// with BMFR's per-tap acceptance (stages/reproject.cpp, bilinear taps, no box fallback) and
// temporal accumulation (stages/temporal_accumulation.cpp), written operation for operation as the
// CPU stages, in two passes as the CPU's: temporalGather() (demodulate, reproject) and, once the
// history trust (history_trust_block.h) is known, temporalBlend(). Compiled without contracting
// multiply-adds (temporal.cu: --fmad=false), it gives the CPU's results bit for bit
// (tests/unit/core/cuda/test_cuda_emulated.cpp checks this on the CPU).
#pragma once

#include "cuda/device_math.h"
#include "cuda/history_trust_block.h"

namespace afn::cuda {

/// Values that change every frame, read by the kernels from device memory (so that one captured
/// graph serves every frame).
struct FrameConstants {
    int hasHistory = 0; ///< 0 on the first frame after a reset
    int useCamera = 0; ///< this frame's and the previous frame's cameras are both valid
    float prevViewProjection[16] = {}; ///< row-vector convention, clip = [p, 1] * M
    float pixelOffset[2] = { 0.5f, 0.5f }; ///< this frame's sub-pixel offset
    // Settings (stages/reproject.h ReprojectSettings, temporal_accumulation.h).
    float positionLimit = 4.0f;
    float positionLimitSquared = 0.0f;
    float normalLimitSquared = 0.25f;
    float depthLimit = 0.1f;
    float alphaMin = 0.2f;
    float antilag = 1.0f; ///< stages/history_trust.h HistoryTrustSettings (0: no trust measured)
    float taaAlpha = 0.7f; ///< methods/afn/settings.h Settings::taaAlpha
    int taaHistory = 0; ///< the TAA's history holds the previous frame (set by the pipeline)
    int auxMode = 0; ///< stages/aux_prefilter.h AuxSettings::Mode: 0 auto, 1 clean, 2 noisy
    int spp = 0; ///< AuxSettings::spp (0: unknown)
    int colorDemodulated = 0; ///< the colour input is already irradiance
    /// afn's highlight bypass factor (methods/afn/settings.h Settings::highlights, 0 = off;
    /// the default is stages/highlight_bypass.h kHighlightFactor, checked in frame_constants.h)
    float highlights = 8.0f;
};

/// Buffers of the first stage (frame size, interleaved floats; optional inputs null when absent).
struct TemporalBuffers {
    int width = 0;
    int height = 0;
    const float* color = nullptr; ///< 3 ch
    const float* albedo = nullptr; ///< 3 ch
    const float* motion = nullptr; ///< 2 ch, pixels, pointing to the previous frame
    const float* position = nullptr; ///< 3 ch, this frame
    const float* prevPosition = nullptr;
    const float* normal = nullptr; ///< 3 ch, this frame
    const float* prevNormal = nullptr;
    const float* depth = nullptr; ///< 1 ch, this frame
    const float* prevDepth = nullptr;
    const float* prevAccumulated = nullptr; ///< 3 ch, the previous frame's output
    const float* prevHistoryLength = nullptr; ///< 1 ch
    float* irradiance = nullptr; ///< 3 ch out: demodulated colour
    /// 3 ch out; between temporalGather() and temporalBlend() the reprojected history
    float* accumulated = nullptr;
    /// 1 ch out; between the two the history's length, or kNoHistoryDevice where it has none
    float* historyLength = nullptr;
};

namespace temporal {

AFN_HD float dist2(const float* a, const float* b)
{
    const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

AFN_HD bool isZero3(const float* v)
{
    return v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f;
}

/// World-space size of pixel (x, y) (Reprojector::footprint).
AFN_HD float footprint(const TemporalBuffers& b, int x, int y)
{
    const float* p = b.position + 3 * (static_cast<std::size_t>(y) * b.width + x);
    float result = 0.0f;
    for (int axis = 0; axis < 2; ++axis) {
        const int dx = axis == 0 ? 1 : 0, dy = axis == 0 ? 0 : 1;
        float best = -1.0f;
        for (int s = -1; s <= 1; s += 2) {
            const int nx = x + s * dx, ny = y + s * dy;
            if (nx < 0 || ny < 0 || nx >= b.width || ny >= b.height)
                continue;
            const float d
                = sqrtf(dist2(p, b.position + 3 * (static_cast<std::size_t>(ny) * b.width + nx)));
            if (best < 0.0f || d < best)
                best = d;
        }
        const float a = maxOf(best, 0.0f);
        result = axis == 0 ? a : maxOf(result, a);
    }
    return result;
}

/// Where pixel (x, y) was in the previous frame (Reprojector::previousPosition).
AFN_HD bool previousPosition(
    const TemporalBuffers& b, const FrameConstants& f, int x, int y, float& px, float& py)
{
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    if (b.motion) {
        px = static_cast<float>(x) + b.motion[2 * i];
        py = static_cast<float>(y) + b.motion[2 * i + 1];
    } else if (b.position && f.useCamera) {
        const float* p = b.position + 3 * i;
        const float* M = f.prevViewProjection;
        const float cx = p[0] * M[0] + p[1] * M[4] + p[2] * M[8] + M[12];
        const float cy = p[0] * M[1] + p[1] * M[5] + p[2] * M[9] + M[13];
        const float cw = p[0] * M[3] + p[1] * M[7] + p[2] * M[11] + M[15];
        if (!(cw > 0.0f))
            return false;
        const float u = (cx / cw + 1.0f) * 0.5f, v = (cy / cw + 1.0f) * 0.5f;
        px = u * static_cast<float>(b.width) - f.pixelOffset[0];
        py = v * static_cast<float>(b.height) - (1.0f - f.pixelOffset[1]);
    } else {
        px = static_cast<float>(x);
        py = static_cast<float>(y);
    }
    return fabsf(px) < 1e7f && fabsf(py) < 1e7f;
}

/// Whether history tap (tx, ty) is accepted for pixel (x, y) (Reprojector::accept).
AFN_HD bool accept(
    const TemporalBuffers& b, const FrameConstants& f, int x, int y, int tx, int ty, float fp)
{
    if (tx < 0 || ty < 0 || tx >= b.width || ty >= b.height)
        return false;
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    const std::size_t t = static_cast<std::size_t>(ty) * b.width + tx;
    if (b.position) {
        const float d2 = dist2(b.prevPosition + 3 * t, b.position + 3 * i);
        if (f.positionLimitSquared > 0.0f) {
            if (!(d2 < f.positionLimitSquared))
                return false;
        } else {
            const float lim = f.positionLimit * fp;
            if (!(d2 == 0.0f || d2 < lim * lim))
                return false;
        }
    } else if (b.depth) {
        const float z = b.depth[i];
        const float dz = fabsf(b.prevDepth[t] - z);
        if (!(dz == 0.0f || dz < f.depthLimit * fabsf(z)))
            return false;
    }
    if (b.normal) {
        const float* n = b.normal + 3 * i;
        const float* np = b.prevNormal + 3 * t;
        if (isZero3(n) || isZero3(np))
            return false;
        if (!(dist2(n, np) < f.normalLimitSquared))
            return false;
    }
    return true;
}

} // namespace temporal

/// The bilinear history taps of pixel (x, y) into the previous frame, each of weight 0 unless
/// accepted (Reprojector's taps, no box fallback); false without a previous position.
struct HistoryTaps {
    int x0 = 0, y0 = 0; ///< tap k at (x0 + (k & 1), y0 + (k >> 1))
    float bilinear[4] = { 0.0f, 0.0f, 0.0f, 0.0f }; ///< the bilinear weights (TAA samples them)
    float w[4] = { 0.0f, 0.0f, 0.0f, 0.0f }; ///< the bilinear weight where accepted, else 0
    AFN_HD std::size_t index(int width, int k) const
    {
        return static_cast<std::size_t>(y0 + (k >> 1)) * width + x0 + (k & 1);
    }
};

AFN_HD bool historyTaps(
    const TemporalBuffers& b, const FrameConstants& f, int x, int y, HistoryTaps& t)
{
    using namespace temporal;
    float px = 0.0f, py = 0.0f;
    if (!f.hasHistory || !previousPosition(b, f, x, y, px, py))
        return false;
    const float fx0 = floorf(px), fy0 = floorf(py);
    t.x0 = static_cast<int>(fx0);
    t.y0 = static_cast<int>(fy0);
    const float fx = px - fx0, fy = py - fy0;
    const bool usePosition = b.position && !(f.positionLimitSquared > 0.0f);
    const float fp = usePosition ? footprint(b, x, y) : 0.0f;
    const float bw[4] = { (1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy };
    for (int k = 0; k < 4; ++k) {
        t.bilinear[k] = bw[k];
        t.w[k] = accept(b, f, x, y, t.x0 + (k & 1), t.y0 + (k >> 1), fp) ? bw[k] : 0.0f;
    }
    return true;
}

/// Demodulate and reproject pixel (x, y): writes its irradiance, and its reprojected history and
/// that history's length into `accumulated` and `historyLength` (kNoHistoryDevice where none
/// was accepted: TemporalAccumulator::gatherRows()).
AFN_HD void temporalGather(const TemporalBuffers& b, const FrameConstants& f, int x, int y)
{
    using namespace temporal;
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    // Demodulation.
    const bool divide = b.albedo && !f.colorDemodulated;
    for (int k = 0; k < 3; ++k) {
        const float d = divide ? b.color[3 * i + k] / albedoFactor(b.albedo[3 * i + k], false)
                               : b.color[3 * i + k];
        b.irradiance[3 * i + k] = clampIrradiance(d);
    }
    // Reprojection: accepted bilinear taps, then their renormalised history.
    float prev[3] = { 0.0f, 0.0f, 0.0f };
    float sppS = 0.0f, ws = 0.0f;
    HistoryTaps taps;
    if (historyTaps(b, f, x, y, taps)) {
        // gatherHistory<3> and gatherHistory<1> over the same taps.
        float sppW = 0.0f;
        for (int k = 0; k < 4; ++k) {
            if (!(taps.w[k] > 0.0f))
                continue;
            const std::size_t t = taps.index(b.width, k);
            for (int ch = 0; ch < 3; ++ch)
                prev[ch] += taps.w[k] * b.prevAccumulated[3 * t + ch];
            ws += taps.w[k];
            sppS += taps.w[k] * b.prevHistoryLength[t];
            sppW += taps.w[k];
        }
        if (ws > 0.0f)
            for (int ch = 0; ch < 3; ++ch)
                prev[ch] /= ws;
        if (sppW > 0.0f)
            sppS /= sppW;
    }
    if (!(ws > 0.0f)) {
        b.historyLength[i] = kNoHistoryDevice;
        return;
    }
    for (int k = 0; k < 3; ++k)
        b.accumulated[3 * i + k] = prev[k];
    b.historyLength[i] = sppS;
}

/// prev + alpha * (cur - prev), below FLT_MIN in magnitude flushed to 0 (stages/reproject.h
/// blendHistory()).
AFN_HD float blendHistoryDevice(float prev, float cur, float alpha)
{
    const float v = prev + alpha * (cur - prev);
    return fabsf(v) < 1.17549435e-38f ? 0.0f : v;
}

/// Accumulate pixel (x, y) after temporalGather() with history trust `trust` (1: none measured):
/// TemporalAccumulator::blendPixel() and blendRows().
AFN_HD void temporalBlend(
    const TemporalBuffers& b, const FrameConstants& f, float trust, int x, int y)
{
    const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
    const float* c = b.irradiance + 3 * i;
    float* acc = b.accumulated + 3 * i;
    float sppS = b.historyLength[i];
    if (sppS == kNoHistoryDevice) {
        for (int k = 0; k < 3; ++k)
            acc[k] = c[k];
        b.historyLength[i] = 1.0f;
        return;
    }
    float alpha = maxOf(1.0f / (sppS + 1.0f), f.alphaMin);
    if (trust < 1.0f) {
        alpha += (1.0f - alpha) * (1.0f - trust);
        sppS *= trust;
    }
    for (int k = 0; k < 3; ++k)
        acc[k] = blendHistoryDevice(acc[k], c[k], alpha);
    b.historyLength[i] = alpha < 1.0f ? minOf(sppS + 1.0f, 255.0f) : 1.0f;
}

} // namespace afn::cuda
