// SPDX-License-Identifier: Apache-2.0
// BMFR blockwise regression: per block, a Householder QR of the feature matrix with the colour
// channels appended as extra columns, back substitution, and the weighted feature sum (see
// methods/bmfr/denoiser.h).
//
// Choices (the official code runs on a GPU with fp16 buffers):
//   - Scaled features (positions or their screen-space stand-ins) are min-max normalised per block
//     as BMFR does: (v - min) / (max - min) if max - min > 1, else v - min. Squares are taken of
//     the scaled values: {1, p, p^2} and {1, a p + b, (a p + b)^2} span the same space, so the fit
//     is BMFR's while the numbers stay O(1).
//   - The noise (uniform in [-noise, noise], a hash of pixel, frame and feature: deterministic and
//     independent of the thread count) is added after scaling to every feature but the constant.
//   - Colour is centred on its block mean (computed in double) before the fit and the mean added
//     back after: a constant block is reproduced exactly.
//   - Pixels whose colour was divided by an albedo below kAlbedoEpsilon in some channel (black
//     albedo: their irradiance is amplified up to 1024x, see stages/demodulate.h) are left out of
//     the fit (zero rows do not change a least-squares QR) and keep their accumulated value, so
//     they neither pollute their block nor get polluted by it.
//   - Out-of-image block pixels are mirrored into the image (BMFR reflects at the borders), so
//   every
//     block has blockSize^2 rows. The 16 block offsets below are our own values in BMFR's range
//     [-16, 14] (cycle of frameIndex % 16), not the official table.
#include "methods/bmfr/denoiser.h"

#include "base/parallel.h"
#include "stages/demodulate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace afn::bmfr {

namespace {

constexpr int kOffsets[16][2] = { { -16, -16 }, { -8, 0 }, { 0, -8 }, { -12, -4 }, { -4, -12 },
    { 8, -16 }, { -16, 8 }, { 4, 4 }, { -10, 10 }, { 10, -10 }, { 14, -2 }, { -2, 14 }, { 6, -6 },
    { -6, 6 }, { 12, 12 }, { 2, -14 } };

/// Reflect a coordinate into [0, n) (period 2n).
inline int mirror(int v, int n)
{
    const int period = 2 * n;
    int m = v % period;
    if (m < 0)
        m += period;
    return m < n ? m : period - 1 - m;
}

/// Uniform value in [-1, 1] from a 32-bit integer hash (lowbias32).
inline float hashNoise(std::uint32_t x, std::uint32_t y, std::uint32_t frame, std::uint32_t k)
{
    std::uint32_t h
        = x * 0x9E3779B1u ^ (y * 0x85EBCA77u) ^ (frame * 0xC2B2AE3Du) ^ (k * 0x27D4EB2Fu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return static_cast<float>(h >> 8) * (2.0f / 16777215.0f) - 1.0f;
}

/// First block start <= 0 for an offset.
inline int gridStart(int offset, int b)
{
    int s = offset;
    while (s > 0)
        s -= b;
    while (s + b <= 0)
        s += b;
    return s;
}

/// True if the pixel's irradiance came from a division by the albedo floor (see the file comment).
inline bool unreliable(const Frame& f, int x, int y)
{
    if (!f.hasAlbedo() || f.colorDemodulated)
        return false;
    const float* a = f.albedo.at(x, y);
    return a[0] < kAlbedoEpsilon || a[1] < kAlbedoEpsilon || a[2] < kAlbedoEpsilon;
}

/// Most features of a Layout: 1 + 3 normals + 2 * 3 scaled.
constexpr int kMaxFeatures = 10;

struct Layout {
    int normals = 0; ///< 0 or 3 unscaled normal features
    int scaled = 0; ///< 2 or 3 scaled features (position, or x, y [, depth])
    int features() const { return 1 + normals + 2 * scaled; }
};

/// Raw scaled-group values of pixel (x, y).
inline void scaledRaw(const Frame& f, int x, int y, int count, float* v)
{
    if (f.hasPosition()) {
        const float* p = f.position.at(x, y);
        v[0] = p[0];
        v[1] = p[1];
        v[2] = p[2];
        return;
    }
    v[0] = static_cast<float>(x);
    v[1] = static_cast<float>(y);
    if (count == 3)
        v[2] = f.depth(x, y, 0);
}

/// Householder QR of the first `nf` columns of the column-major n x (nf + 3) matrix `a`, applied to
/// all columns; then back substitution into `w` (nf x 3). Near-singular pivots get weight 0.
void solveBlock(std::vector<double>& a, int n, int nf, double* w)
{
    const int cols = nf + 3;
    thread_local std::vector<double> v;
    v.resize(static_cast<std::size_t>(n));
    for (int k = 0; k < nf; ++k) {
        double* ak = &a[static_cast<std::size_t>(k) * n];
        double norm2 = 0.0;
        for (int i = k; i < n; ++i)
            norm2 += ak[i] * ak[i];
        const double norm = std::sqrt(norm2);
        if (norm == 0.0)
            continue;
        const double alpha = ak[k] > 0.0 ? -norm : norm;
        double vn2 = 0.0;
        for (int i = k; i < n; ++i) {
            v[i] = ak[i] - (i == k ? alpha : 0.0);
            vn2 += v[i] * v[i];
        }
        if (vn2 == 0.0)
            continue;
        for (int j = k; j < cols; ++j) {
            double* aj = &a[static_cast<std::size_t>(j) * n];
            double s = 0.0;
            for (int i = k; i < n; ++i)
                s += v[i] * aj[i];
            const double f = 2.0 * s / vn2;
            if (f == 0.0)
                continue;
            for (int i = k; i < n; ++i)
                aj[i] -= f * v[i];
        }
    }
    double maxDiag = 0.0;
    for (int k = 0; k < nf; ++k)
        maxDiag = std::max(maxDiag, std::fabs(a[static_cast<std::size_t>(k) * n + k]));
    for (int c = 0; c < 3; ++c) {
        const double* b = &a[static_cast<std::size_t>(nf + c) * n];
        for (int k = nf - 1; k >= 0; --k) {
            const double rkk = a[static_cast<std::size_t>(k) * n + k];
            double s = b[k];
            for (int j = k + 1; j < nf; ++j)
                s -= a[static_cast<std::size_t>(j) * n + k] * w[j * 3 + c];
            w[k * 3 + c] = std::fabs(rkk) > 1e-7 * maxDiag && rkk != 0.0 ? s / rkk : 0.0;
        }
    }
}

/// Copy the in-image pixels of the block at (bx0, by0) from `src` to `dst` (3 ch).
void copyBlock(const Image& src, int bx0, int by0, int B, Image& dst)
{
    for (int y = std::max(by0, 0); y < std::min(by0 + B, src.height()); ++y)
        for (int x = std::max(bx0, 0); x < std::min(bx0 + B, src.width()); ++x)
            for (int c = 0; c < 3; ++c)
                dst(x, y, c) = src(x, y, c);
}

} // namespace

void regression(const Frame& f, const Image& noisy, const Settings& s, int blockFrame,
    Image& filtered, const WorkRegion* region)
{
    const int W = f.width, H = f.height, B = s.blockSize, n = B * B;
    Layout L;
    L.normals = f.hasNormal() ? 3 : 0;
    L.scaled = f.hasPosition() || f.hasDepth() ? 3 : 2;
    const int nf = L.features();
    const int* off = kOffsets[((blockFrame % 16) + 16) % 16];
    const int sx = gridStart(off[0], B), sy = gridStart(off[1], B);
    const int nbx = (W - sx + B - 1) / B, nby = (H - sy + B - 1) / B;
    filtered.resize(W, H, 3);
    const std::uint32_t frameKey = static_cast<std::uint32_t>(f.frameIndex);

    parallelFor(nbx * nby, [&](int blockIndex) {
        const int bx0 = sx + (blockIndex % nbx) * B, by0 = sy + (blockIndex / nbx) * B;
        if (region && !region->intersects(bx0, by0, bx0 + B, by0 + B)) {
            copyBlock(noisy, bx0, by0, B, filtered); // work skipping: the cheap path
            return;
        }
        // Per-thread scratch, reused from block to block: a fresh 130 KB matrix per block was an
        // mmap, page faults and munmap each time. Every element read below is written first.
        thread_local std::vector<double> a;
        thread_local std::vector<float> feat;
        a.resize(static_cast<std::size_t>(n) * (nf + 3));
        feat.resize(static_cast<std::size_t>(n) * nf);
        // Load raw features and colour.
        float lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
        double mean[3] = { 0, 0, 0 };
        int used = 0;
        for (int r = 0; r < n; ++r) {
            const int x = mirror(bx0 + r % B, W), y = mirror(by0 + r / B, H);
            if (unreliable(f, x, y))
                continue;
            ++used;
            float* fr = &feat[static_cast<std::size_t>(r) * nf];
            fr[0] = 1.0f;
            for (int k = 0; k < L.normals; ++k)
                fr[1 + k] = f.normal(x, y, k);
            float* sc = fr + 1 + L.normals;
            scaledRaw(f, x, y, L.scaled, sc);
            for (int k = 0; k < L.scaled; ++k) {
                lo[k] = used == 1 ? sc[k] : std::min(lo[k], sc[k]);
                hi[k] = used == 1 ? sc[k] : std::max(hi[k], sc[k]);
            }
            const float* c = noisy.at(x, y);
            for (int k = 0; k < 3; ++k)
                mean[k] += c[k];
        }
        float meanF[3];
        for (int k = 0; k < 3; ++k)
            meanF[k] = used ? static_cast<float>(mean[k] / used) : 0.0f;
        for (int r = 0; r < n; ++r) {
            const int x = mirror(bx0 + r % B, W), y = mirror(by0 + r / B, H);
            float* fr = &feat[static_cast<std::size_t>(r) * nf];
            if (unreliable(f, x, y)) { // zero row: no influence on the fit
                for (int k = 0; k < nf + 3; ++k)
                    a[static_cast<std::size_t>(k) * n + r] = 0.0;
                continue;
            }
            float* sc = fr + 1 + L.normals;
            for (int k = 0; k < L.scaled; ++k) {
                const float range = hi[k] - lo[k];
                if (std::isfinite(range))
                    sc[k] = range > 1.0f ? (sc[k] - lo[k]) / range : sc[k] - lo[k];
                else // hi - lo beyond FLT_MAX (values near +-3.4e38): scale in double
                    sc[k] = static_cast<float>((static_cast<double>(sc[k]) - lo[k])
                        / (static_cast<double>(hi[k]) - lo[k]));
                sc[L.scaled + k] = sc[k] * sc[k];
            }
            for (int k = 1; k < nf; ++k)
                fr[k] += s.noise
                    * hashNoise(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                        frameKey, static_cast<std::uint32_t>(k));
            for (int k = 0; k < nf; ++k)
                a[static_cast<std::size_t>(k) * n + r] = fr[k];
            const float* c = noisy.at(x, y);
            for (int k = 0; k < 3; ++k)
                a[static_cast<std::size_t>(nf + k) * n + r] = static_cast<double>(c[k]) - meanF[k];
        }
        double w[kMaxFeatures * 3] = {};
        solveBlock(a, n, nf, w);
        // Weighted sum for the block's in-image pixels.
        for (int r = 0; r < n; ++r) {
            const int x = bx0 + r % B, y = by0 + r / B;
            if (x < 0 || y < 0 || x >= W || y >= H)
                continue;
            if (unreliable(f, x, y)) {
                for (int c = 0; c < 3; ++c)
                    filtered(x, y, c) = noisy(x, y, c);
                continue;
            }
            const float* fr = &feat[static_cast<std::size_t>(r) * nf];
            for (int c = 0; c < 3; ++c) {
                double v = 0.0;
                for (int k = 0; k < nf; ++k)
                    v += w[k * 3 + c] * fr[k];
                const float out = meanF[c] + static_cast<float>(v);
                filtered(x, y, c) = out > 0.0f ? std::min(out, kMaxIrradiance) : 0.0f;
            }
        }
    });
}

} // namespace afn::bmfr
