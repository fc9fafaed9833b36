// SPDX-License-Identifier: Apache-2.0
// Image-quality metrics: per-pixel sums and the SSIM map, reduced per fixed row blocks (see
// metrics/metrics.h).
#include "metrics/metrics.h"

#include "base/exception.h"
#include "base/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace afn::metrics {

namespace {

/// Rows per reduction block. Fixed (not derived from the thread count) so sums are reproducible.
constexpr int kBlockRows = 16;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

int numBlocks(int rows)
{
    return (rows + kBlockRows - 1) / kBlockRows;
}

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
    if (v.empty())
        throwInvalidArgument(std::string("metrics: ") + what + " image is empty");
    if (v.channels < 3)
        throwInvalidArgument(std::string("metrics: ") + what + " image has "
            + std::to_string(v.channels) + " channels; at least 3 (RGB) are needed");
}

void checkSameSize(const ImageView& a, const ImageView& b, const char* what)
{
    if (a.width != b.width || a.height != b.height)
        throwInvalidArgument(std::string("metrics: ") + what + " size " + std::to_string(b.width)
            + "x" + std::to_string(b.height) + " does not match the test image "
            + std::to_string(a.width) + "x" + std::to_string(a.height));
}

double quantize8(double t)
{
    return std::floor(255.0 * t + 0.5) / 255.0;
}

/// Sums over linear values of one block of rows.
struct LinearSums {
    double sq = 0.0; // sum (o - t)^2
    double smape = 0.0; // sum |o - t| / (|o| + |t| + eps)
    std::int64_t nonFiniteTest = 0;
    std::int64_t nonFiniteRef = 0;
};

/// Sums over one tone-mapped channel: errors of T(x) and of its 8-bit version, and the sums of the
/// SSIM maps (float and 8-bit) over the pixels whose window fits.
struct ChannelSums {
    double sq = 0.0; // sum (T(o) - T(t))^2
    double smape = 0.0; // sum |T(o) - T(t)| / (T(o) + T(t) + eps)
    double sq8 = 0.0; // sum (Q(T(o)) - Q(T(t)))^2
    double ssim = 0.0; // sum of the SSIM map
    double ssim8 = 0.0; // sum of the SSIM map of the 8-bit values
};

/// SSIM window side for an image (the largest odd size <= 7 that fits; see metrics/metrics.h).
int ssimWindow(int width, int height)
{
    int win = std::min(kSsimWindow, std::min(width, height));
    return win % 2 ? win : win - 1;
}

/// Sum of the SSIM map over `outRows` output rows, skimage conventions (metrics/metrics.h). `a` and
/// `b` hold outRows + win - 1 rows of `width` values; output row r, column x uses the window whose
/// top-left value is (r, x). `hs` is scratch.
double ssimRowsSum(
    const double* a, const double* b, int outRows, int width, int win, std::vector<double>& hs)
{
    const int rows = outRows + win - 1, cols = width - win + 1;
    const double np = static_cast<double>(win) * win;
    const double covNorm = win > 1 ? np / (np - 1.0) : 1.0; // sample covariance (skimage default)
    const double c1 = 0.01 * 0.01; // (K1 * data_range)^2, data_range = 1
    const double c2 = 0.03 * 0.03; // (K2 * data_range)^2
    const std::size_t need = static_cast<std::size_t>(rows) * cols * 5;
    if (hs.size() < need)
        hs.resize(need);
    // Horizontal window sums of x, y, xx, yy, xy (direct sums: the same order for every pixel).
    for (int r = 0; r < rows; ++r) {
        const double* ra = a + static_cast<std::size_t>(r) * width;
        const double* rb = b + static_cast<std::size_t>(r) * width;
        for (int x = 0; x < cols; ++x) {
            double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
            for (int k = 0; k < win; ++k) {
                const double va = ra[x + k], vb = rb[x + k];
                sx += va, sy += vb, sxx += va * va, syy += vb * vb, sxy += va * vb;
            }
            double* o = &hs[(static_cast<std::size_t>(r) * cols + x) * 5];
            o[0] = sx, o[1] = sy, o[2] = sxx, o[3] = syy, o[4] = sxy;
        }
    }
    double sum = 0.0;
    for (int r = 0; r < outRows; ++r) {
        for (int x = 0; x < cols; ++x) {
            double s[5] = { 0, 0, 0, 0, 0 };
            for (int k = 0; k < win; ++k) {
                const double* o = &hs[(static_cast<std::size_t>(r + k) * cols + x) * 5];
                for (int q = 0; q < 5; ++q)
                    s[q] += o[q];
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
    return sum;
}

/// Per-thread scratch of channelSums, kept between blocks and calls: allocating (and page-faulting)
/// full-image planes cost more than the arithmetic.
struct Scratch {
    std::vector<double> ta, tb, qa, qb, hs;
};

/// All tone-mapped sums of channel c, one fused pass per fixed block of rows: T(x) is evaluated
/// for the block's rows plus the SSIM window's halo, in thread-local rows.
ChannelSums channelSums(const ImageView& test, const ImageView& reference, int c)
{
    const int w = test.width, h = test.height;
    const int win = ssimWindow(w, h), pad = (win - 1) / 2;
    std::vector<ChannelSums> partial(numBlocks(h));
    forRowBlocks(0, h, [&](int block, int y0, int y1) {
        thread_local Scratch sc;
        // SSIM output rows of this block, and the rows whose T(x) they and the sums need.
        const int o0 = std::max(y0, pad), o1 = std::min(y1, h - pad);
        const int r0 = o0 < o1 ? std::min(y0, o0 - pad) : y0;
        const int r1 = o0 < o1 ? std::max(y1, o1 + pad) : y1;
        const std::size_t n = static_cast<std::size_t>(r1 - r0) * w;
        for (std::vector<double>* v : { &sc.ta, &sc.tb, &sc.qa, &sc.qb })
            if (v->size() < n)
                v->resize(n);
        for (int y = r0; y < r1; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = static_cast<std::size_t>(y - r0) * w + x;
                sc.ta[i] = evalToneMap(test.at(x, y)[c]);
                sc.tb[i] = evalToneMap(reference.at(x, y)[c]);
                sc.qa[i] = quantize8(sc.ta[i]);
                sc.qb[i] = quantize8(sc.tb[i]);
            }
        ChannelSums s;
        for (std::size_t i = static_cast<std::size_t>(y0 - r0) * w;
             i < static_cast<std::size_t>(y1 - r0) * w; ++i) {
            const double d = sc.ta[i] - sc.tb[i], d8 = sc.qa[i] - sc.qb[i];
            s.sq += d * d;
            s.smape += std::abs(d) / (sc.ta[i] + sc.tb[i] + kSmapeEpsilon);
            s.sq8 += d8 * d8;
        }
        if (o0 < o1) {
            const std::size_t first = static_cast<std::size_t>(o0 - pad - r0) * w;
            s.ssim = ssimRowsSum(&sc.ta[first], &sc.tb[first], o1 - o0, w, win, sc.hs);
            s.ssim8 = ssimRowsSum(&sc.qa[first], &sc.qb[first], o1 - o0, w, win, sc.hs);
        }
        partial[block] = s;
    });
    ChannelSums sum;
    for (const ChannelSums& p : partial) {
        sum.sq += p.sq, sum.smape += p.smape, sum.sq8 += p.sq8;
        sum.ssim += p.ssim, sum.ssim8 += p.ssim8;
    }
    return sum;
}

/// Number of pixels the SSIM map is averaged over.
double ssimCount(int width, int height)
{
    const int win = ssimWindow(width, height);
    return static_cast<double>(width - win + 1) * (height - win + 1);
}

} // namespace

double evalToneMap(double x)
{
    if (std::isnan(x))
        return x;
    // 1/2.2, written 0.454545 in WSKPN's code; the difference is below float precision of T.
    return std::clamp(std::pow(std::max(x, 0.0), 1.0 / 2.2), 0.0, 1.0);
}

double psnrFromMse(double mse)
{
    if (std::isnan(mse))
        return kNaN;
    if (mse <= 0.0)
        return kInf;
    return 10.0 * std::log10(1.0 / mse);
}

double ssimChannel(const ImageView& a, const ImageView& b, int c, bool q8)
{
    checkView(a, "test");
    checkView(b, "reference");
    checkSameSize(a, b, "reference");
    if (c < 0 || c >= 3)
        throwInvalidArgument("metrics: channel must be 0, 1 or 2");
    const ChannelSums s = channelSums(a, b, c);
    return (q8 ? s.ssim8 : s.ssim) / ssimCount(a.width, a.height);
}

FrameMetrics computeFrameMetrics(const ImageView& test, const ImageView& reference)
{
    checkView(test, "test");
    checkView(reference, "reference");
    checkSameSize(test, reference, "reference");
    const int w = test.width, h = test.height;

    // Linear values: squared error, SMAPE, and the non-finite count.
    std::vector<LinearSums> partial(numBlocks(h));
    forRowBlocks(0, h, [&](int block, int y0, int y1) {
        LinearSums s;
        for (int y = y0; y < y1; ++y) {
            for (int x = 0; x < w; ++x) {
                const float* o = test.at(x, y);
                const float* t = reference.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    const double ov = o[c], tv = t[c];
                    if (!std::isfinite(ov))
                        ++s.nonFiniteTest;
                    if (!std::isfinite(tv))
                        ++s.nonFiniteRef;
                    const double d = ov - tv;
                    s.sq += d * d;
                    s.smape += std::abs(d) / (std::abs(ov) + std::abs(tv) + kSmapeEpsilon);
                }
            }
        }
        partial[block] = s;
    });
    LinearSums lin;
    for (const LinearSums& p : partial) {
        lin.sq += p.sq;
        lin.smape += p.smape;
        lin.nonFiniteTest += p.nonFiniteTest;
        lin.nonFiniteRef += p.nonFiniteRef;
    }

    FrameMetrics m;
    m.nonFiniteTest = lin.nonFiniteTest;
    m.nonFiniteReference = lin.nonFiniteRef;
    if (m.nonFiniteTest > 0 || m.nonFiniteReference > 0) {
        // Never skip a broken pixel: the whole frame scores NaN (see metrics/metrics.h).
        m.psnr = m.ssim = m.rmse = m.smape = m.rmseLinear = m.smapeTonemapped = kNaN;
        m.psnr8 = m.ssim8 = m.rmse8 = kNaN;
        return m;
    }

    // Tone-mapped values, one channel at a time (one fused pass per channel): squared error,
    // SMAPE, 8-bit squared error, and SSIM per channel averaged over the three channels
    // (skimage's channel_axis behaviour).
    ChannelSums tm;
    for (int c = 0; c < 3; ++c) {
        const ChannelSums cs = channelSums(test, reference, c);
        tm.sq += cs.sq, tm.smape += cs.smape, tm.sq8 += cs.sq8;
        tm.ssim += cs.ssim / ssimCount(w, h), tm.ssim8 += cs.ssim8 / ssimCount(w, h);
    }
    const double n = 3.0 * static_cast<double>(w) * h;
    const double mse = tm.sq / n, mse8 = tm.sq8 / n;
    m.psnr = psnrFromMse(mse);
    m.rmse = std::sqrt(mse);
    m.psnr8 = psnrFromMse(mse8);
    m.rmse8 = std::sqrt(mse8);
    m.rmseLinear = std::sqrt(lin.sq / n);
    m.smape = lin.smape / n;
    m.smapeTonemapped = tm.smape / n;
    m.ssim = tm.ssim / 3.0; // mean over channels of the per-channel mean SSIM
    m.ssim8 = tm.ssim8 / 3.0;
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
                        if (!std::isfinite(px[i][c]))
                            ++s.nonFinite;
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

} // namespace afn::metrics
