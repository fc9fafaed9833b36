// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (methods/afn/post_filter.h: the formula and its reasoning;
// post_filter_noise.h: the luminance term's per-pixel scale) on the CUDA engine, one pixel at a
// time: postFilterGuidePixel() writes the sanitised guide planes and the scale (the CPU's
// arithmetic, without contraction: post_filter_guides.cpp and post_filter_noise.cpp), then the six
// half-passes (steps 1, 2, 4; horizontal, then vertical) each run postFilterHalfPixel() over the
// frame, ping-ponging between two colour buffers. The half-passes evaluate the CPU row kernel's
// formula in its order with the same exponential polynomial; the CPU contracts their
// multiply-adds in some instruction-set clones, the GPU in all, so their results agree to float
// rounding, not bit for bit.
#pragma once

#include "cuda/device_math.h"

#include <cstddef>

namespace afn::cuda {

// methods/afn/post_filter.h, post_filter_noise.h, post_filter_row.cpp (afn_pipeline.cpp checks the
// header constants).
constexpr int kPostFilterIterationsDevice = 3;
constexpr float kPostFilterSigmaLuminanceDevice = 0.25f;
constexpr float kPostFilterNoiseReferenceDevice = 0.85f;
constexpr float kPostFilterNoiseClampDevice = 4.0f;
constexpr float kPostFilterMinExponent = -40.0f;
constexpr float kPostFilterMinNormalCosine = 0.3f;
constexpr float kPostFilterAlbedoScale = 1.0f / 0.1f;
constexpr float kPostFilterDepthRelative = 0.02f;

/// The guide planes (frame size, one float per pixel each).
struct PostFilterPlanes {
    float *a0 = nullptr, *a1 = nullptr, *a2 = nullptr; ///< albedo (non-finite, absent: 0)
    float *n0 = nullptr, *n1 = nullptr, *n2 = nullptr; ///< unit normal (invalid: 0)
    float* nv = nullptr; ///< 1 where the normal is valid
    float* z = nullptr; ///< depth (non-finite: 1e30; absent: 1)
    float* ls = nullptr; ///< the luminance term's scale (post_filter_noise.h)
};

/// What the guides are made from (frame size, interleaved; absent inputs null).
struct PostFilterSources {
    int width = 0;
    int height = 0;
    const float* albedo = nullptr; ///< 3 ch, the frame's after the aux prefilter
    const float* normal = nullptr; ///< 3 ch
    const float* depth = nullptr; ///< 1 ch
    const float* irradiance = nullptr; ///< 3 ch, the 1-spp demodulated colour
    const float* historyLength = nullptr; ///< 1 ch, the accumulation's
    float maxSamples = 9.0f; ///< (2 - alphaMin) / alphaMin
};

/// The samples an accumulation with minimum blend alphaMin keeps at most
/// (TemporalAccumulator::effectiveSamplesLimit()).
AFN_HD float effectiveSamplesLimit(float alphaMin)
{
    return alphaMin > 0.0f ? (2.0f - alphaMin) / alphaMin : 255.0f;
}

namespace postfilter {

AFN_HD float finiteOr(float v, float otherwise)
{
    return fabsf(v) <= 3.402823466e38f ? v : otherwise;
}

AFN_HD int clampIndex(int v, int lo, int hi)
{
    return v < lo ? lo : (hi < v ? hi : v);
}

/// Rec. 709 luminance of pixel (x, y) of the irradiance, non-finite channels 0.
AFN_HD float noiseLuminance(const PostFilterSources& s, int x, int y)
{
    const float* c = s.irradiance + 3 * (static_cast<std::size_t>(y) * s.width + x);
    return 0.2126f * finiteOr(c[0], 0.0f) + 0.7152f * finiteOr(c[1], 0.0f)
        + 0.0722f * finiteOr(c[2], 0.0f);
}

/// e^x for x <= 0 (post_filter_row.cpp expNonPositiveV(): relative error < 3e-6), 0 below
/// e^-40 and for NaN.
AFN_HD float expNonPositive(float xIn)
{
    const bool kept = xIn >= kPostFilterMinExponent; // false for NaN
    const float x = kept ? xIn : kPostFilterMinExponent;
    const float t = x * 1.44269504f;
    const int whole = static_cast<int>(t) + (t < 0.0f ? -1 : 0);
    const float f = t - static_cast<float>(whole);
    float p = 1.352060e-2f;
    p = p * f + 5.203743e-2f;
    p = p * f + 2.414275e-1f;
    p = p * f + 6.930066e-1f;
    p = p * f + 1.0000025f;
    const float scale = bitsFloat(static_cast<std::uint32_t>(whole + 127) << 23);
    return kept ? p * scale : 0.0f;
}

} // namespace postfilter

/// The guide planes and the luminance scale of pixel (x, y).
AFN_HD void postFilterGuidePixel(
    const PostFilterSources& s, const PostFilterPlanes& g, int x, int y)
{
    using namespace postfilter;
    const int w = s.width, h = s.height;
    const std::size_t i = static_cast<std::size_t>(y) * w + x;
    if (s.albedo) {
        g.a0[i] = finiteOr(s.albedo[3 * i], 0.0f);
        g.a1[i] = finiteOr(s.albedo[3 * i + 1], 0.0f);
        g.a2[i] = finiteOr(s.albedo[3 * i + 2], 0.0f);
    } else {
        g.a0[i] = g.a1[i] = g.a2[i] = 0.0f;
    }
    if (s.normal) {
        const float n0 = s.normal[3 * i], n1 = s.normal[3 * i + 1], n2 = s.normal[3 * i + 2];
        const float len2 = n0 * n0 + n1 * n1 + n2 * n2;
        const bool ok = len2 > 0.5f && len2 <= 3.402823466e38f; // not ~0, NaN or infinite
        const float inv = 1.0f / sqrtf(ok ? len2 : 1.0f);
        g.n0[i] = ok ? n0 * inv : 0.0f;
        g.n1[i] = ok ? n1 * inv : 0.0f;
        g.n2[i] = ok ? n2 * inv : 0.0f;
        g.nv[i] = ok ? 1.0f : 0.0f;
    } else {
        g.n0[i] = g.n1[i] = g.n2[i] = g.nv[i] = 0.0f;
    }
    g.z[i] = s.depth ? finiteOr(s.depth[i], 1e30f) : 1.0f;
    // The scale (post_filter_noise.cpp): the 5x5 box (taps clamped to the border) of l and l^2,
    // along x per row, then along y.
    const float base = 0.5f * kPostFilterSigmaLuminanceDevice;
    if (!s.irradiance) {
        g.ls[i] = base;
        return;
    }
    constexpr float kInverseTaps = 1.0f / 5.0f;
    float s1 = 0.0f, s2 = 0.0f;
    for (int dy = -2; dy <= 2; ++dy) {
        const int qy = clampIndex(y + dy, 0, h - 1);
        float r1 = 0.0f, r2 = 0.0f;
        for (int dx = -2; dx <= 2; ++dx) {
            const float v = noiseLuminance(s, clampIndex(x + dx, 0, w - 1), qy);
            r1 += v;
            r2 += v * v;
        }
        s1 += r1 * kInverseTaps;
        s2 += r2 * kInverseTaps;
    }
    const float mean = s1 * kInverseTaps, variance = s2 * kInverseTaps - mean * mean;
    const float maxSamples = s.maxSamples < 1.0f ? 1.0f : s.maxSamples;
    float samples = s.historyLength ? s.historyLength[i] : 1.0f;
    samples = samples >= 1.0f ? (maxSamples < samples ? maxSamples : samples) : 1.0f; // NaN too
    const float noise = sqrtf((variance < 0.0f ? 0.0f : variance) / samples)
        / ((mean < 0.0f ? 0.0f : mean) + 1e-3f);
    const float sc = noise * (base / kPostFilterNoiseReferenceDevice);
    const float lo = base / kPostFilterNoiseClampDevice, hi = base * kPostFilterNoiseClampDevice;
    g.ls[i] = sc >= lo ? (sc <= hi ? sc : hi) : lo; // NaN takes the low end
}

/// One half-pass at pixel (x, y): `in` and `out` frame-size, 3 floats per pixel.
AFN_HD void postFilterHalfPixel(const PostFilterPlanes& g, const float* in, float* out, int w,
    int h, int x, int y, bool horizontal, int step)
{
    using namespace postfilter;
    constexpr float kSpline[5]
        = { 1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f };
    const std::size_t i = static_cast<std::size_t>(y) * w + x;
    const float r = in[3 * i], gr = in[3 * i + 1], b = in[3 * i + 2];
    const float l = 0.2126f * r + 0.7152f * gr + 0.0722f * b;
    const float z = g.z[i];
    const float zmax = z > 1e-3f ? z : 1e-3f;
    float invDepth[2];
    for (int ring = 1; ring <= 2; ++ring)
        invDepth[ring - 1] = 1.0f
            / (kPostFilterDepthRelative * static_cast<float>(step) * static_cast<float>(ring) * zmax
                + 1e-6f);
    float ar = kSpline[2] * r, ag = kSpline[2] * gr, ab = kSpline[2] * b, aw = kSpline[2];
    for (int j = -2; j <= 2; ++j) {
        if (j == 0)
            continue;
        const int qx = horizontal ? clampIndex(x + j * step, 0, w - 1) : x;
        const int qy = horizontal ? y : clampIndex(y + j * step, 0, h - 1);
        const std::size_t q = static_cast<std::size_t>(qy) * w + qx;
        const float q0 = in[3 * q], q1 = in[3 * q + 1], q2 = in[3 * q + 2];
        const float lq = 0.2126f * q0 + 0.7152f * q1 + 0.0722f * q2;
        const float sum = l + lq, diff = l - lq;
        float e = fabsf(diff) / (g.ls[i] * (sum > 0.0f ? sum : 0.0f) + 1e-3f);
        e += (fabsf(g.a0[i] - g.a0[q]) + fabsf(g.a1[i] - g.a1[q]) + fabsf(g.a2[i] - g.a2[q]))
            * kPostFilterAlbedoScale;
        e += fabsf(z - g.z[q]) * invDepth[(j < 0 ? -j : j) - 1];
        float d = g.n0[i] * g.n0[q] + g.n1[i] * g.n1[q] + g.n2[i] * g.n2[q];
        d = d > kPostFilterMinNormalCosine ? d : 0.0f;
        for (int k = 0; k < 6; ++k) // ^64
            d *= d;
        const float both = g.nv[i] * g.nv[q]; // 1 where both normals are valid, else 0
        const float wt = kSpline[j + 2] * expNonPositive(-e) * (1.0f + both * (d - 1.0f));
        ar += wt * q0;
        ag += wt * q1;
        ab += wt * q2;
        aw += wt;
    }
    const float inv = 1.0f / aw; // >= the centre tap's weight 3/8 > 0
    out[3 * i] = ar * inv;
    out[3 * i + 1] = ag * inv;
    out[3 * i + 2] = ab * inv;
}

} // namespace afn::cuda
