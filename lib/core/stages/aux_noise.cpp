// SPDX-License-Identifier: Apache-2.0
// Speckle estimate of auxiliary buffers (see stages/aux_noise.h).
#include "stages/aux_noise.h"

#include "base/parallel.h"
#include "cpu/isa.h"
#include "stages/aux_noise_rows.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace afn {

namespace {

bool hasSurface(float z)
{
    return std::isfinite(z) && std::fabs(z) < kAuxDepthSky;
}

/// dist(p, q) of the kind (see the header); +inf when q cannot be compared with p.
template <AuxKind K> inline float distance(const float* p, const float* q)
{
    if constexpr (K == AuxKind::Albedo) {
        const float d
            = std::max({ std::fabs(p[0] - q[0]), std::fabs(p[1] - q[1]), std::fabs(p[2] - q[2]) });
        const float level = std::max({ p[0], p[1], p[2], q[0], q[1], q[2], kAuxAlbedoLevelFloor });
        return d / level;
    } else if constexpr (K == AuxKind::Normal) {
        const float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    } else {
        if (!hasSurface(q[0]))
            return std::numeric_limits<float>::infinity();
        return std::fabs(p[0] - q[0]) / std::max(std::min(std::fabs(p[0]), std::fabs(q[0])), 1e-6f);
    }
}

/// Whether the pixel at `p` is speckle: its distance to every comparable neighbour exceeds `t`.
/// The neighbours are visited in a fixed order and the visit stops at the first one within `t`
/// (then min <= t and the pixel is not speckle): clean buffers cost about one distance per pixel,
/// and the answer is the one of the full minimum (NaN distances are skipped either way, as
/// std::min(best, NaN) keeps best). `inner`: all 8 neighbours lie in the image.
template <AuxKind K>
inline bool isSpeckle(const ImageView& img, int x, int y, const float* p, float t, bool inner)
{
    static constexpr int kDx[8] = { -1, 1, 0, 0, -1, 1, -1, 1 };
    static constexpr int kDy[8] = { 0, 0, -1, 1, -1, -1, 1, 1 };
    float best = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 8; ++k) {
        const int qx = x + kDx[k], qy = y + kDy[k];
        if (!inner && (qx < 0 || qy < 0 || qx >= img.width || qy >= img.height))
            continue;
        const float d = distance<K>(p, img.at(qx, qy));
        if (d <= t)
            return false;
        best = std::min(best, d);
    }
    // A pixel without comparable neighbours (1x1 image, surface pixel amid sky) is not called
    // speckle: there is nothing to compare it with. Every finite distance seen was above t.
    return std::isfinite(best);
}

/// Flags of rows [y0, y1) into `flags` (when not null); returns their count.
template <AuxKind K>
std::int64_t flagRows(const ImageView& img, float t, Image* flags, int y0, int y1)
{
    const int w = img.width, h = img.height;
    // AVX-512: the left-neighbour test of 16 inner pixels at once (aux_noise_avx512.cpp); the
    // pixels it does not settle take the scalar test.
    const int channels = K == AuxKind::Depth ? 1 : 3;
    const bool vector = cpu::activeIsa() == cpu::Isa::Avx512 && img.channels == channels
        && img.pixelStride == static_cast<std::ptrdiff_t>(channels * sizeof(float));
    std::int64_t count = 0;
    for (int y = y0; y < y1; ++y) {
        const bool innerRow = y > 0 && y < h - 1;
        auto pixel = [&](int x) {
            const float* p = img.at(x, y);
            const bool speckle = (K != AuxKind::Depth || hasSurface(p[0]))
                && isSpeckle<K>(img, x, y, p, t, innerRow && x > 0 && x < w - 1);
            if (flags)
                (*flags)(x, y, 0) = speckle ? 1.0f : 0.0f;
            count += speckle ? 1 : 0;
        };
        int x = 0;
        if (vector && innerRow) {
            pixel(x++);
            for (; x + 16 <= w - 1; x += 16) {
                const std::uint32_t within = K == AuxKind::Depth
                    ? depthSettled16(img.at(x, y), t)
                    : leftNeighbourWithin16(img.at(x, y), K, t);
                // Settled lanes are not speckle; the others take the scalar test.
                if (flags)
                    for (std::uint32_t m = within & 0xFFFFu; m != 0; m &= m - 1)
                        (*flags)(x + __builtin_ctz(m), y, 0) = 0.0f;
                for (std::uint32_t m = ~within & 0xFFFFu; m != 0; m &= m - 1)
                    pixel(x + __builtin_ctz(m));
            }
        }
        for (; x < w; ++x)
            pixel(x);
    }
    return count;
}

float threshold(AuxKind kind)
{
    switch (kind) {
    case AuxKind::Albedo:
        return AuxNoiseThresholds::albedo;
    case AuxKind::Normal:
        return AuxNoiseThresholds::normal;
    case AuxKind::Depth:
        return AuxNoiseThresholds::depth;
    }
    return 0.0f;
}

} // namespace

namespace {

std::int64_t speckleRows(const ImageView& img, AuxKind kind, Image* flags)
{
    const float t = threshold(kind);
    std::atomic<std::int64_t> total { 0 };
    parallelRows(img.height, [&](int y0, int y1) {
        switch (kind) {
        case AuxKind::Albedo:
            total += flagRows<AuxKind::Albedo>(img, t, flags, y0, y1);
            break;
        case AuxKind::Normal:
            total += flagRows<AuxKind::Normal>(img, t, flags, y0, y1);
            break;
        case AuxKind::Depth:
            total += flagRows<AuxKind::Depth>(img, t, flags, y0, y1);
            break;
        }
    });
    return total;
}

} // namespace

std::int64_t speckleFlags(const ImageView& img, AuxKind kind, Image& flags)
{
    if (img.empty()) {
        flags = Image();
        return 0;
    }
    flags.resize(img.width, img.height, 1);
    return speckleRows(img, kind, &flags);
}

std::int64_t speckleCount(const ImageView& img, AuxKind kind)
{
    return img.empty() ? 0 : speckleRows(img, kind, nullptr);
}

namespace {

template <AuxKind K> void discontinuityRows(const ImageView& img, Image& out, int y0, int y1)
{
    static constexpr int kDx[4] = { -1, 1, 0, 0 };
    static constexpr int kDy[4] = { 0, 0, -1, 1 };
    const float t = threshold(K);
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* p = img.at(x, y);
            int n = 0, far = 0;
            for (int k = 0; k < 4; ++k) {
                const int qx = x + kDx[k], qy = y + kDy[k];
                if (qx < 0 || qy < 0 || qx >= img.width || qy >= img.height)
                    continue;
                ++n;
                far += distance<K>(p, img.at(qx, qy)) > t ? 1 : 0; // NaN: not far
            }
            out(x, y, 0) = n > 0 ? static_cast<float>(far) / static_cast<float>(n) : 0.0f;
        }
}

} // namespace

void discontinuityShares(const ImageView& img, AuxKind kind, Image& out)
{
    if (img.empty() || kind == AuxKind::Depth) {
        out = Image();
        return;
    }
    out.resize(img.width, img.height, 1);
    parallelRows(img.height, [&](int y0, int y1) {
        if (kind == AuxKind::Albedo)
            discontinuityRows<AuxKind::Albedo>(img, out, y0, y1);
        else
            discontinuityRows<AuxKind::Normal>(img, out, y0, y1);
    });
}

double speckleShare(const ImageView& img, AuxKind kind)
{
    if (img.empty())
        return 0.0;
    const std::int64_t n = speckleCount(img, kind);
    return static_cast<double>(n) / (static_cast<double>(img.width) * img.height);
}

} // namespace afn
