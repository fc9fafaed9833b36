// SPDX-License-Identifier: Apache-2.0
// Speckle estimate of auxiliary buffers (see stages/aux_noise.h).
#include "stages/aux_noise.h"

#include "base/parallel.h"

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

/// Flags of rows [y0, y1); returns their count. Pixels with all 8 neighbours in the image take a
/// path without bounds checks (same neighbours, same order, same result).
template <AuxKind K>
std::int64_t flagRows(const ImageView& img, float t, Image& flags, int y0, int y1)
{
    const int w = img.width, h = img.height;
    std::int64_t count = 0;
    for (int y = y0; y < y1; ++y) {
        const bool innerRow = y > 0 && y < h - 1;
        for (int x = 0; x < w; ++x) {
            const float* p = img.at(x, y);
            bool speckle = false;
            if (K != AuxKind::Depth || hasSurface(p[0])) {
                float best = std::numeric_limits<float>::infinity();
                if (innerRow && x > 0 && x < w - 1) {
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx)
                            if (dx != 0 || dy != 0)
                                best = std::min(best, distance<K>(p, img.at(x + dx, y + dy)));
                } else {
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const int qx = x + dx, qy = y + dy;
                            if ((dx == 0 && dy == 0) || qx < 0 || qy < 0 || qx >= w || qy >= h)
                                continue;
                            best = std::min(best, distance<K>(p, img.at(qx, qy)));
                        }
                }
                // A pixel without comparable neighbours (1x1 image, surface pixel amid sky) is not
                // called speckle: there is nothing to compare it with.
                speckle = std::isfinite(best) && best > t;
            }
            flags(x, y, 0) = speckle ? 1.0f : 0.0f;
            count += speckle ? 1 : 0;
        }
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

std::int64_t speckleFlags(const ImageView& img, AuxKind kind, Image& flags)
{
    if (img.empty()) {
        flags = Image();
        return 0;
    }
    const int w = img.width, h = img.height;
    flags.resize(w, h, 1);
    const float t = threshold(kind);
    std::atomic<std::int64_t> total { 0 };
    parallelRows(h, [&](int y0, int y1) {
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

double speckleShare(const ImageView& img, AuxKind kind)
{
    if (img.empty())
        return 0.0;
    Image flags;
    const std::int64_t n = speckleFlags(img, kind, flags);
    return static_cast<double>(n) / (static_cast<double>(img.width) * img.height);
}

} // namespace afn
