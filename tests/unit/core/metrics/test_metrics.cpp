// SPDX-License-Identifier: Apache-2.0
// Metrics of lib/core/metrics: hand-computed values on tiny images, a naive SSIM written from the
// formula, thread-count determinism, and SSIM/PSNR against scikit-image (skipped if not installed).
#include "base/exception.h"
#include "metrics/metrics.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using afn::Image;

const double kInf = std::numeric_limits<double>::infinity();

/// Deterministic pseudo-random values in [lo, hi) (LCG; independent of the library).
Image noiseImage(int w, int h, int ch, std::uint32_t seed, float lo, float hi)
{
    Image img(w, h, ch);
    std::uint32_t s = seed;
    for (std::size_t i = 0; i < img.size(); ++i) {
        s = s * 1664525u + 1013904223u;
        img.data()[i] = lo + (hi - lo) * static_cast<float>(s >> 8) / 16777216.0f;
    }
    return img;
}

/// The evaluation tone map written again here from the notes' formula (not the library's).
double naiveT(double x)
{
    return std::min(1.0, std::pow(std::max(x, 0.0), 1.0 / 2.2));
}

/// SSIM straight from Wang et al. / skimage: for every pixel whose 7x7 window fits, direct window
/// means, sample variances and covariance; mean of the map; mean over the 3 channels.
double naiveSsim(const Image& a, const Image& b, int win = 7)
{
    const int pad = win / 2;
    const double n = win * win, c1 = 1e-4, c2 = 9e-4;
    double total = 0.0;
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        int count = 0;
        for (int y = pad; y < a.height() - pad; ++y) {
            for (int x = pad; x < a.width() - pad; ++x) {
                double mx = 0, my = 0;
                for (int j = -pad; j <= pad; ++j)
                    for (int i = -pad; i <= pad; ++i) {
                        mx += naiveT(a(x + i, y + j, c)) / n;
                        my += naiveT(b(x + i, y + j, c)) / n;
                    }
                double vx = 0, vy = 0, cxy = 0;
                for (int j = -pad; j <= pad; ++j)
                    for (int i = -pad; i <= pad; ++i) {
                        const double dx = naiveT(a(x + i, y + j, c)) - mx;
                        const double dy = naiveT(b(x + i, y + j, c)) - my;
                        vx += dx * dx / (n - 1);
                        vy += dy * dy / (n - 1);
                        cxy += dx * dy / (n - 1);
                    }
                sum += (2 * mx * my + c1) * (2 * cxy + c2)
                    / ((mx * mx + my * my + c1) * (vx + vy + c2));
                ++count;
            }
        }
        total += sum / count;
    }
    return total / 3.0;
}

TEST(Metrics, ToneMap)
{
    EXPECT_EQ(afn::metrics::evalToneMap(-1.0), 0.0);
    EXPECT_EQ(afn::metrics::evalToneMap(0.0), 0.0);
    EXPECT_EQ(afn::metrics::evalToneMap(1.0), 1.0);
    EXPECT_EQ(afn::metrics::evalToneMap(4.0), 1.0);
    EXPECT_DOUBLE_EQ(afn::metrics::evalToneMap(0.25), std::pow(0.25, 1.0 / 2.2));
    EXPECT_TRUE(std::isnan(afn::metrics::evalToneMap(std::nan(""))));
}

TEST(Metrics, PsnrFromMse)
{
    EXPECT_DOUBLE_EQ(afn::metrics::psnrFromMse(0.01), 20.0);
    EXPECT_DOUBLE_EQ(afn::metrics::psnrFromMse(1.0), 0.0);
    EXPECT_EQ(afn::metrics::psnrFromMse(0.0), kInf);
}

TEST(Metrics, IdenticalImages)
{
    const Image a = noiseImage(9, 8, 4, 7, -0.2f, 3.0f);
    const afn::metrics::FrameMetrics m = afn::metrics::computeFrameMetrics(a.view(), a.view());
    EXPECT_EQ(m.psnr, kInf);
    EXPECT_EQ(m.psnr8, kInf);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.rmseLinear, 0.0);
    EXPECT_EQ(m.smape, 0.0);
    EXPECT_EQ(m.smapeTonemapped, 0.0);
    EXPECT_NEAR(m.ssim, 1.0, 1e-12);
    EXPECT_NEAR(m.ssim8, 1.0, 1e-12);
    EXPECT_EQ(m.nonFiniteTest, 0);
}

TEST(Metrics, OneWrongValueOn2x2)
{
    // Reference black; the test differs in one of 2x2x3 = 12 values: 4.0 (T = 1).
    Image ref(2, 2, 3, 0.0f), test(2, 2, 3, 0.0f);
    test(1, 0, 2) = 4.0f;
    const afn::metrics::FrameMetrics m = afn::metrics::computeFrameMetrics(test.view(), ref.view());
    EXPECT_NEAR(m.psnr, 10.0 * std::log10(12.0), 1e-12); // MSE on T = 1/12
    EXPECT_NEAR(m.rmse, std::sqrt(1.0 / 12.0), 1e-12);
    EXPECT_NEAR(m.rmseLinear, std::sqrt(16.0 / 12.0), 1e-12);
    EXPECT_NEAR(m.smape, (4.0 / 4.001) / 12.0, 1e-12);
    EXPECT_NEAR(m.smapeTonemapped, (1.0 / 1.001) / 12.0, 1e-12);
    EXPECT_NEAR(m.psnr8, m.psnr, 1e-12); // 0 and 1 are exact in 8 bits
}

TEST(Metrics, SmapeOfKnownPairs)
{
    // Pairs (o, t) per value; SMAPE = mean |o - t| / (|o| + |t| + 0.001).
    Image test(1, 1, 3), ref(1, 1, 3);
    const float o[3] = { 1.0f, -2.0f, 0.0f }, t[3] = { 3.0f, 2.0f, 0.0f };
    for (int c = 0; c < 3; ++c)
        test(0, 0, c) = o[c], ref(0, 0, c) = t[c];
    const double expected = (2.0 / 4.001 + 4.0 / 4.001 + 0.0) / 3.0;
    EXPECT_NEAR(afn::metrics::computeFrameMetrics(test.view(), ref.view()).smape, expected, 1e-12);
}

TEST(Metrics, NegativeValuesClampInToneMappedMetrics)
{
    Image ref(3, 3, 3, 0.0f), test(3, 3, 3, -1.0f);
    const afn::metrics::FrameMetrics m = afn::metrics::computeFrameMetrics(test.view(), ref.view());
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.psnr, kInf);
    EXPECT_NEAR(m.rmseLinear, 1.0, 1e-12);
}

TEST(Metrics, NonFiniteIsCountedAndMakesTheFrameNaN)
{
    Image ref(8, 8, 3, 0.5f), test(8, 8, 3, 0.5f);
    test(3, 4, 1) = std::numeric_limits<float>::quiet_NaN();
    test(5, 5, 0) = std::numeric_limits<float>::infinity();
    ref(0, 0, 2) = -std::numeric_limits<float>::infinity();
    const afn::metrics::FrameMetrics m = afn::metrics::computeFrameMetrics(test.view(), ref.view());
    EXPECT_EQ(m.nonFiniteTest, 2);
    EXPECT_EQ(m.nonFiniteReference, 1);
    for (double v : { m.psnr, m.ssim, m.rmse, m.smape, m.rmseLinear, m.smapeTonemapped, m.psnr8,
             m.ssim8, m.rmse8 })
        EXPECT_TRUE(std::isnan(v));
}

TEST(Metrics, SsimOfTwoConstantsByHand)
{
    // Constant planes: variances 0, so SSIM = (2ab + C1) / (a^2 + b^2 + C1) with C1 = 1e-4.
    Image white(8, 8, 3, 1.0f), black(8, 8, 3, 0.0f);
    const afn::metrics::FrameMetrics m
        = afn::metrics::computeFrameMetrics(white.view(), black.view());
    EXPECT_NEAR(m.ssim, 1e-4 / 1.0001, 1e-15);
    EXPECT_NEAR(m.ssim8, 1e-4 / 1.0001, 1e-15);
}

TEST(Metrics, SsimMatchesNaiveFormula)
{
    const Image a = noiseImage(23, 17, 3, 1, -0.1f, 1.5f);
    const Image b = noiseImage(23, 17, 3, 2, -0.1f, 1.5f);
    Image c = a; // a slightly perturbed copy: SSIM near 1
    for (std::size_t i = 0; i < c.size(); i += 5)
        c.data()[i] *= 1.1f;
    EXPECT_NEAR(afn::metrics::computeFrameMetrics(a.view(), b.view()).ssim, naiveSsim(a, b), 1e-10);
    EXPECT_NEAR(afn::metrics::computeFrameMetrics(c.view(), a.view()).ssim, naiveSsim(c, a), 1e-10);
}

TEST(Metrics, SmallImagesShrinkTheWindow)
{
    const Image a = noiseImage(5, 4, 3, 3, 0.0f, 1.0f);
    const Image b = noiseImage(5, 4, 3, 4, 0.0f, 1.0f);
    EXPECT_NEAR(
        afn::metrics::computeFrameMetrics(a.view(), b.view()).ssim, naiveSsim(a, b, 3), 1e-10);
    const Image p = noiseImage(1, 1, 3, 5, 0.0f, 1.0f);
    EXPECT_NEAR(afn::metrics::computeFrameMetrics(p.view(), p.view()).ssim, 1.0, 1e-12);
}

TEST(Metrics, RejectsBadInputs)
{
    Image a(4, 4, 3), b(5, 4, 3), g(4, 4, 1);
    EXPECT_THROW(afn::metrics::computeFrameMetrics(a.view(), b.view()), afn::Exception);
    EXPECT_THROW(afn::metrics::computeFrameMetrics(g.view(), g.view()), afn::Exception);
    EXPECT_THROW(afn::metrics::computeFrameMetrics(afn::ImageView(), a.view()), afn::Exception);
    EXPECT_THROW(afn::metrics::computeTemporalMetrics(a.view(), a.view(), a.view(), b.view()),
        afn::Exception);
}

TEST(Metrics, DeterministicAcrossThreadCounts)
{
    const Image a = noiseImage(97, 131, 3, 11, -0.5f, 4.0f);
    const Image b = noiseImage(97, 131, 3, 12, -0.5f, 4.0f);
    afn::metrics::FrameMetrics m[3];
    afn::metrics::TemporalMetrics t[3];
    const int threads[3] = { 1, 2, 3 };
    for (int i = 0; i < 3; ++i) {
        tbb::task_arena arena(threads[i]);
        arena.execute([&] {
            m[i] = afn::metrics::computeFrameMetrics(a.view(), b.view());
            t[i] = afn::metrics::computeTemporalMetrics(b.view(), a.view(), a.view(), b.view());
        });
    }
    for (int i = 1; i < 3; ++i) {
        EXPECT_EQ(std::memcmp(&m[0], &m[i], sizeof(afn::metrics::FrameMetrics)), 0);
        EXPECT_EQ(std::memcmp(&t[0], &t[i], sizeof(afn::metrics::TemporalMetrics)), 0);
    }
}

TEST(Metrics, TemporalGradientByHand)
{
    // The reference is static; the test changes one of 12 values from 0 to 4 (T: 0 -> 1).
    Image ref(2, 2, 3, 0.25f), prev(2, 2, 3, 0.0f), cur(2, 2, 3, 0.0f);
    cur(0, 1, 1) = 4.0f;
    afn::metrics::TemporalMetrics m
        = afn::metrics::computeTemporalMetrics(prev.view(), cur.view(), ref.view(), ref.view());
    EXPECT_NEAR(m.gradientError, 1.0 / 12.0, 1e-12);
    EXPECT_NEAR(m.gradientPsnr, 10.0 * std::log10(12.0), 1e-12);
    // A test that changes exactly as the reference does: no temporal error, whatever its bias.
    Image refPrev(2, 2, 3, 0.0f), refCur(2, 2, 3, 0.0f);
    refCur(0, 1, 1) = 4.0f;
    m = afn::metrics::computeTemporalMetrics(
        prev.view(), cur.view(), refPrev.view(), refCur.view());
    EXPECT_EQ(m.gradientError, 0.0);
    EXPECT_EQ(m.gradientPsnr, kInf);
    cur(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
    m = afn::metrics::computeTemporalMetrics(
        prev.view(), cur.view(), refPrev.view(), refCur.view());
    EXPECT_EQ(m.nonFinite, 1);
    EXPECT_TRUE(std::isnan(m.gradientError));
}

// ---- scikit-image as the independent implementation ---------------------------------------------

bool haveSkimage()
{
    return std::system("/usr/bin/python3 -c 'import skimage.metrics' >/dev/null 2>&1") == 0;
}

void writeRaw(const std::string& path, const Image& img)
{
    std::vector<double> d(
        img.data(), img.data() + img.size()); // float64 so skimage works in double
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(d.data()), static_cast<std::streamsize>(d.size() * 8));
}

TEST(Metrics, MatchesScikitImage)
{
    if (!haveSkimage())
        GTEST_SKIP() << "python3-skimage is not installed (scripts/setup.sh)";
    const int w = 41, h = 29;
    const Image a = noiseImage(w, h, 3, 21, -0.2f, 1.6f);
    Image b = a;
    const Image n = noiseImage(w, h, 3, 22, -0.3f, 0.3f);
    for (std::size_t i = 0; i < b.size(); ++i)
        b.data()[i] += n.data()[i];
    const std::string dir = ::testing::TempDir();
    const std::string pa = dir + "afn_metrics_a.f64", pb = dir + "afn_metrics_b.f64";
    const std::string out = dir + "afn_metrics_skimage.txt";
    writeRaw(pa, a);
    writeRaw(pb, b);
    // T(x) is applied in numpy; uint8 images use skimage's default data_range (255) for uint8.
    std::ostringstream py;
    py << "import numpy as np\n"
       << "from skimage.metrics import structural_similarity as ssim, peak_signal_noise_ratio as "
          "psnr\n"
       << "T = lambda x: np.clip(np.maximum(x, 0) ** (1 / 2.2), 0, 1)\n"
       << "a = T(np.fromfile('" << pa << "', dtype='<f8').reshape(" << h << ", " << w << ", 3))\n"
       << "b = T(np.fromfile('" << pb << "', dtype='<f8').reshape(" << h << ", " << w << ", 3))\n"
       << "q = lambda x: np.floor(255 * x + 0.5).astype(np.uint8)\n"
       << "v = [ssim(b, a, channel_axis=2, data_range=1.0), psnr(a, b, data_range=1.0),\n"
       << "     ssim(q(b), q(a), channel_axis=2), psnr(q(a), q(b))]\n"
       << "open('" << out << "', 'w').write(' '.join(repr(float(x)) for x in v))\n";
    const std::string script = dir + "afn_metrics_skimage.py";
    std::ofstream(script) << py.str();
    ASSERT_EQ(std::system(("/usr/bin/python3 " + script).c_str()), 0);
    double ssimRef = 0, psnrRef = 0, ssim8Ref = 0, psnr8Ref = 0;
    std::ifstream(out) >> ssimRef >> psnrRef >> ssim8Ref >> psnr8Ref;
    const afn::metrics::FrameMetrics m = afn::metrics::computeFrameMetrics(b.view(), a.view());
    EXPECT_GT(ssimRef, 0.3); // the case is neither trivial nor hopeless
    EXPECT_LT(ssimRef, 0.99);
    EXPECT_NEAR(m.ssim, ssimRef, 1e-7);
    EXPECT_NEAR(m.psnr, psnrRef, 1e-6);
    EXPECT_NEAR(m.ssim8, ssim8Ref, 1e-7);
    EXPECT_NEAR(m.psnr8, psnr8Ref, 1e-6);
}

} // namespace
