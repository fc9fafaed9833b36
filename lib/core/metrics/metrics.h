// SPDX-License-Identifier: Apache-2.0
// Image-quality metrics (PSNR, SSIM, RMSE, SMAPE) and a temporal-stability error. Pure compute.
//
// Conventions (docs/metrics.md says the same, with the reasons):
// - Only the first 3 channels of each pixel are compared (RGB); any 4th channel is ignored.
// - T(x) = clip(max(x, 0)^(1/2.2), 0, 1) is the tone map for PSNR, SSIM, RMSE and the "tonemapped"
//   SMAPE (AFN paper and WSKPN evaluation code: exponent 0.454545). R = 1 on T(x).
// - PSNR = 10 log10(1 / MSE) on T(x); +inf when MSE == 0 (identical images).
// - SSIM: the skimage 0.19 `structural_similarity` defaults as WSKPN used them: 7x7 uniform window,
//   K1 = 0.01, K2 = 0.03, sample covariance (N / (N - 1), N = 49), the mean of the SSIM map over
//   the pixels whose window lies inside the image (a (win-1)/2 = 3 pixel border is left out),
//   computed per channel and averaged over channels. data_range = 1 (the range of T(x)). Note:
//   skimage called WITHOUT data_range on float images uses 2 (the float dtype range -1..1); we use
//   1 as the notes' R = 1 says. Images smaller than 7 pixels on a side use the largest odd window
//   that fits (skimage raises an error instead); a 1x1 window gives variances 0.
// - RMSE = sqrt(MSE) on T(x); rmseLinear on the linear values.
// - SMAPE = 1/(3N) sum |o - t| / (|o| + |t| + eps), eps = 1e-3 (AFN Eq. 5), on linear values;
//   smapeTonemapped is the same formula on T(x).
// - 8-bit variants (NBGD's evaluation on PNGs): T(x) quantised to round(255 T) / 255 before
//   PSNR / SSIM / RMSE (round half up; PNG writers round, a truncating writer would differ).
// - Non-finite values (NaN, +-Inf) are never skipped: they are counted, and when any is present in
//   either image every metric of that frame is NaN (clearly bad; it propagates into sequence
//   means).
// - Sequences: the per-sequence value of a metric is the mean of its per-frame values.
// - Determinism: sums are taken per fixed block of rows (in double), then the blocks are added in
//   order, so the results do not depend on the number of threads.
#pragma once

#include "base/image.h"

#include <cstdint>

namespace afn::metrics {

/// Metrics of one test image against its reference (see the file comment for definitions).
struct FrameMetrics {
    double psnr = 0.0; ///< dB on T(x), R = 1; +inf for identical images
    double ssim = 0.0; ///< [-1, 1] on T(x); 1 for identical images
    double rmse = 0.0; ///< [0, 1] on T(x)
    double smape = 0.0; ///< [0, 1] on linear values, eps = 1e-3
    double rmseLinear = 0.0; ///< >= 0 on linear values
    double smapeTonemapped = 0.0; ///< [0, 1] on T(x), eps = 1e-3
    double psnr8 = 0.0; ///< dB on T(x) quantised to 8 bits
    double ssim8 = 0.0; ///< SSIM on T(x) quantised to 8 bits
    double rmse8 = 0.0; ///< RMSE on T(x) quantised to 8 bits
    std::int64_t nonFiniteTest = 0; ///< NaN/Inf values in the first 3 channels of the test
    std::int64_t nonFiniteReference
        = 0; ///< NaN/Inf values in the first 3 channels of the reference
};

/// Temporal-stability errors of frame t against frame t-1 (see temporalMetrics).
struct TemporalMetrics {
    double gradientError = 0.0; ///< mean |e|, e = (T(o_t) - T(o_t-1)) - (T(r_t) - T(r_t-1)); >= 0
    double gradientPsnr = 0.0; ///< 10 log10(1 / mean e^2) in dB; +inf when e == 0 everywhere
    std::int64_t nonFinite = 0; ///< NaN/Inf values in the four images (first 3 channels)
};

/// SMAPE's epsilon (AFN Eq. 5).
constexpr double kSmapeEpsilon = 1e-3;
/// SSIM window side (skimage default for uniform windows).
constexpr int kSsimWindow = 7;

/// The evaluation tone map T(x) = clip(max(x, 0)^(1/2.2), 0, 1). NaN stays NaN.
double evalToneMap(double x);

/// PSNR in dB for a mean squared error on a [0, 1] range: 10 log10(1 / mse); +inf when mse == 0.
double psnrFromMse(double mse);

/// All metrics of `test` against `reference`. Both need >= 3 channels and the same size; throws
/// afn::Exception (invalid argument) otherwise. Runs on the calling thread's TBB arena.
FrameMetrics computeFrameMetrics(const ImageView& test, const ImageView& reference);

/// Mean SSIM (conventions above) of two single-channel-per-call planes already in [0, 1]:
/// channel `c` of a and b. Exposed for tests.
double ssimChannel(const ImageView& a, const ImageView& b, int c, bool quantize8);

/// Temporal-gradient errors of the test pair (prev, cur) against the reference pair, on T(x).
/// All four images need the same size and >= 3 channels. Non-finite values make both fields NaN.
TemporalMetrics computeTemporalMetrics(const ImageView& testPrev, const ImageView& test,
    const ImageView& referencePrev, const ImageView& reference);

} // namespace afn::metrics
