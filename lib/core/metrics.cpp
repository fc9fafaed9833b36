// SPDX-License-Identifier: Apache-2.0
// Image-quality metrics: per-pixel sums and the SSIM map, reduced per fixed row blocks (see metrics.h).
#include "metrics.h"

#include "exception.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace afn {

namespace {

/// Rows per reduction block. Fixed (not derived from the thread count) so sums are reproducible.
constexpr int kBlockRows = 16;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

int numBlocks(int rows) { return (rows + kBlockRows - 1) / kBlockRows; }

/// Call fn(block, y0, y1) for every fixed block of rows in [begin, end), in parallel.
template <typename Fn> void forRowBlocks(int begin, int end, Fn&& fn)
{
    const int n = numBlocks(end - begin);
    parallelFor(n, [&](int b) {
        const int y0 = begin + b * kBlockRows;
        fn(b, y0, std::min(end, y0 + kBlockRows));
    });
}

void checkView(const ImageView& v, const char* what)
{
    if (v.empty()) throwInvalidArgument(std::string("metrics: ") + what + " image is empty");
    if (v.channels < 3)
        throwInvalidArgument(std::string("metrics: ") + what + " image has " +
                             std::to_string(v.channels) + " channels; at least 3 (RGB) are needed");
}

void checkSameSize(const ImageView& a, const ImageView& b, const char* what)
{
    if (a.width != b.width || a.height != b.height)
        throwInvalidArgument(std::string("metrics: ") + what + " size " + std::to_string(b.width) +
                             "x" + std::to_string(b.height) + " does not match the test image " +
                             std::to_string(a.width) + "x" + std::to_string(a.height));
}

double quantize8(double t) { return std::floor(255.0 * t + 0.5) / 255.0; }

/// Per-pixel sums of one block of rows.
struct PixelSums {
    double sqT = 0.0;      // sum (T(o) - T(t))^2
    double sqLin = 0.0;    // sum (o - t)^2
    double smapeLin = 0.0; // sum |o - t| / (|o| + |t| + eps)
    double smapeT = 0.0;   // same on T(x)
    double sq8 = 0.0;      // sum (Q(T(o)) - Q(T(t)))^2
    std::int64_t nonFiniteTest = 0;
    std::int64_t nonFiniteRef = 0;
};

/// Mean SSIM of two [0, 1] planes (row-major, width x height), skimage conventions (metrics.h).
double ssimPlane(const std::vector<double>& a, const std::vector<double>& b, int width, int height,
                 bool q8)
{
    int win = std::min(kSsimWindow, std::min(width, height));
    if (win % 2 == 0) --win;
    const int pad = (win - 1) / 2;
    const double np = static_cast<double>(win) * win;
    const double covNorm = win > 1 ? np / (np - 1.0) : 1.0; // sample covariance (skimage default)
    const double c1 = 0.01 * 0.01; // (K1 * data_range)^2, data_range = 1
    const double c2 = 0.03 * 0.03; // (K2 * data_range)^2
    const int xBegin = pad, xEnd = width - pad;
    const int yBegin = pad, yEnd = height - pad;
    const int cols = xEnd - xBegin;
    auto value = [&](const std::vector<double>& p, std::size_t i) {
        const double v = p[i];
        return q8 ? quantize8(v) : v;
    };

    std::vector<double> partial(numBlocks(yEnd - yBegin), 0.0);
    forRowBlocks(yBegin, yEnd, [&](int block, int y0, int y1) {
        // Horizontal window sums of x, y, xx, yy, xy for the rows this block's windows cover.
        const int r0 = y0 - pad, rows = (y1 - y0) + 2 * pad;
        std::vector<double> h(static_cast<std::size_t>(rows) * cols * 5);
        for (int r = 0; r < rows; ++r) {
            const std::size_t rowBase = static_cast<std::size_t>(r0 + r) * width;
            for (int x = xBegin; x < xEnd; ++x) {
                double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
                for (int k = -pad; k <= pad; ++k) {
                    const double va = value(a, rowBase + x + k), vb = value(b, rowBase + x + k);
                    sx += va;
                    sy += vb;
                    sxx += va * va;
                    syy += vb * vb;
                    sxy += va * vb;
                }
                double* o = &h[(static_cast<std::size_t>(r) * cols + (x - xBegin)) * 5];
                o[0] = sx, o[1] = sy, o[2] = sxx, o[3] = syy, o[4] = sxy;
            }
        }
        double sum = 0.0;
        for (int y = y0; y < y1; ++y) {
            for (int i = 0; i < cols; ++i) {
                double s[5] = { 0, 0, 0, 0, 0 };
                for (int k = 0; k < win; ++k) {
                    const double* o = &h[(static_cast<std::size_t>(y - y0 + k) * cols + i) * 5];
                    for (int q = 0; q < 5; ++q) s[q] += o[q];
                }
                const double ux = s[0] / np, uy = s[1] / np;
                const double vx = covNorm * (s[2] / np - ux * ux);
                const double vy = covNorm * (s[3] / np - uy * uy);
                const double vxy = covNorm * (s[4] / np - ux * uy);
                const double num = (2.0 * ux * uy + c1) * (2.0 * vxy + c2);
                const double den = (ux * ux + uy * uy + c1) * (vx + vy + c2);
                sum += num / den;
            }
        }
        partial[block] = sum;
    });
    double total = 0.0;
    for (double p : partial) total += p;
    return total / (static_cast<double>(cols) * (yEnd - yBegin));
}

/// Channel c of a view tone-mapped by T(x) into a packed plane (double, as skimage on float64).
std::vector<double> toneMappedPlane(const ImageView& v, int c)
{
    std::vector<double> plane(static_cast<std::size_t>(v.width) * v.height);
    forRowBlocks(0, v.height, [&](int, int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < v.width; ++x)
                plane[static_cast<std::size_t>(y) * v.width + x] = evalToneMap(v.at(x, y)[c]);
    });
    return plane;
}

} // namespace

double evalToneMap(double x)
{
    if (std::isnan(x)) return x;
    // 1/2.2, written 0.454545 in WSKPN's code; the difference is below float precision of T.
    return std::clamp(std::pow(std::max(x, 0.0), 1.0 / 2.2), 0.0, 1.0);
}

double psnrFromMse(double mse)
{
    if (std::isnan(mse)) return kNaN;
    if (mse <= 0.0) return kInf;
    return 10.0 * std::log10(1.0 / mse);
}

double ssimChannel(const ImageView& a, const ImageView& b, int c, bool q8)
{
    checkView(a, "test");
    checkView(b, "reference");
    checkSameSize(a, b, "reference");
    if (c < 0 || c >= std::min(a.channels, b.channels)) throwInvalidArgument("metrics: bad channel");
    return ssimPlane(toneMappedPlane(a, c), toneMappedPlane(b, c), a.width, a.height, q8);
}

FrameMetrics computeFrameMetrics(const ImageView& test, const ImageView& reference)
{
    checkView(test, "test");
    checkView(reference, "reference");
    checkSameSize(test, reference, "reference");
    const int w = test.width, h = test.height;

    std::vector<PixelSums> partial(numBlocks(h));
    forRowBlocks(0, h, [&](int block, int y0, int y1) {
        PixelSums s;
        for (int y = y0; y < y1; ++y) {
            for (int x = 0; x < w; ++x) {
                const float* o = test.at(x, y);
                const float* t = reference.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    const double ov = o[c], tv = t[c];
                    if (!std::isfinite(ov)) ++s.nonFiniteTest;
                    if (!std::isfinite(tv)) ++s.nonFiniteRef;
                    const double d = ov - tv;
                    s.sqLin += d * d;
                    s.smapeLin += std::abs(d) / (std::abs(ov) + std::abs(tv) + kSmapeEpsilon);
                    const double to = evalToneMap(ov), tt = evalToneMap(tv);
                    const double dt = to - tt;
                    s.sqT += dt * dt;
                    s.smapeT += std::abs(dt) / (to + tt + kSmapeEpsilon);
                    const double d8 = quantize8(to) - quantize8(tt);
                    s.sq8 += d8 * d8;
                }
            }
        }
        partial[block] = s;
    });
    PixelSums sum;
    for (const PixelSums& p : partial) {
        sum.sqT += p.sqT;
        sum.sqLin += p.sqLin;
        sum.smapeLin += p.smapeLin;
        sum.smapeT += p.smapeT;
        sum.sq8 += p.sq8;
        sum.nonFiniteTest += p.nonFiniteTest;
        sum.nonFiniteRef += p.nonFiniteRef;
    }

    FrameMetrics m;
    m.nonFiniteTest = sum.nonFiniteTest;
    m.nonFiniteReference = sum.nonFiniteRef;
    if (m.nonFiniteTest > 0 || m.nonFiniteReference > 0) {
        // Never skip a broken pixel: the whole frame scores NaN (see metrics.h).
        m.psnr = m.ssim = m.rmse = m.smape = m.rmseLinear = m.smapeTonemapped = kNaN;
        m.psnr8 = m.ssim8 = m.rmse8 = kNaN;
        return m;
    }
    const double n = 3.0 * static_cast<double>(w) * h;
    const double mse = sum.sqT / n, mse8 = sum.sq8 / n;
    m.psnr = psnrFromMse(mse);
    m.rmse = std::sqrt(mse);
    m.psnr8 = psnrFromMse(mse8);
    m.rmse8 = std::sqrt(mse8);
    m.rmseLinear = std::sqrt(sum.sqLin / n);
    m.smape = sum.smapeLin / n;
    m.smapeTonemapped = sum.smapeT / n;

    // SSIM per channel, then the mean of the three channels (skimage channel_axis behaviour).
    double ssim = 0.0, ssim8 = 0.0;
    for (int c = 0; c < 3; ++c) {
        const std::vector<double> a = toneMappedPlane(test, c);
        const std::vector<double> b = toneMappedPlane(reference, c);
        ssim += ssimPlane(a, b, w, h, false);
        ssim8 += ssimPlane(a, b, w, h, true);
    }
    m.ssim = ssim / 3.0;
    m.ssim8 = ssim8 / 3.0;
    return m;
}

TemporalMetrics computeTemporalMetrics(const ImageView& testPrev, const ImageView& test,
                                       const ImageView& referencePrev, const ImageView& reference)
{
    checkView(test, "test");
    checkView(testPrev, "previous test");
    checkView(reference, "reference");
    checkView(referencePrev, "previous reference");
    checkSameSize(test, testPrev, "previous test");
    checkSameSize(test, reference, "reference");
    checkSameSize(test, referencePrev, "previous reference");
    const int w = test.width, h = test.height;

    struct Sums {
        double abs = 0.0, sq = 0.0;
        std::int64_t nonFinite = 0;
    };
    std::vector<Sums> partial(numBlocks(h));
    forRowBlocks(0, h, [&](int block, int y0, int y1) {
        Sums s;
        for (int y = y0; y < y1; ++y) {
            for (int x = 0; x < w; ++x) {
                const float* px[4] = { test.at(x, y), testPrev.at(x, y), reference.at(x, y),
                                       referencePrev.at(x, y) };
                for (int c = 0; c < 3; ++c) {
                    double t[4];
                    for (int i = 0; i < 4; ++i) {
                        if (!std::isfinite(px[i][c])) ++s.nonFinite;
                        t[i] = evalToneMap(px[i][c]);
                    }
                    const double e = (t[0] - t[1]) - (t[2] - t[3]);
                    s.abs += std::abs(e);
                    s.sq += e * e;
                }
            }
        }
        partial[block] = s;
    });
    Sums sum;
    for (const Sums& p : partial) {
        sum.abs += p.abs;
        sum.sq += p.sq;
        sum.nonFinite += p.nonFinite;
    }
    TemporalMetrics m;
    m.nonFinite = sum.nonFinite;
    if (m.nonFinite > 0) {
        m.gradientError = m.gradientPsnr = kNaN;
        return m;
    }
    const double n = 3.0 * static_cast<double>(w) * h;
    m.gradientError = sum.abs / n;
    m.gradientPsnr = psnrFromMse(sum.sq / n);
    return m;
}

} // namespace afn
