// SPDX-License-Identifier: Apache-2.0
// ColorManager conversions on afn's default config, checked against values derived by hand.
#include "afn/color.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <thread>

using afn::color::ColorError;
using afn::color::ColorManager;

namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

// IEC 61966-2-1 sRGB encoding (the piecewise curve), written out independently of OCIO.
double srgbEncode(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}
double srgbDecode(double v)
{
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Mat3 mul(const Mat3& a, const Mat3& b)
{
    Mat3 r {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                r[i][j] += a[i][k] * b[k][j];
    return r;
}

Mat3 inverse(const Mat3& m)
{
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Mat3 r {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
    return r;
}

std::array<double, 3> xyzOf(double x, double y)
{
    return { x / y, 1.0, (1 - x - y) / y };
}

// RGB -> XYZ from chromaticities (SMPTE RP 177).
Mat3 rgbToXyz(const double prim[3][2], const double white[2])
{
    Mat3 p {};
    for (int c = 0; c < 3; ++c) {
        const auto v = xyzOf(prim[c][0], prim[c][1]);
        for (int r = 0; r < 3; ++r)
            p[r][c] = v[r];
    }
    const auto w = xyzOf(white[0], white[1]);
    const Mat3 pi = inverse(p);
    Mat3 out = p;
    for (int c = 0; c < 3; ++c) {
        const double s = pi[c][0] * w[0] + pi[c][1] * w[1] + pi[c][2] * w[2];
        for (int r = 0; r < 3; ++r)
            out[r][c] *= s;
    }
    return out;
}

// Bradford chromatic adaptation between two white points.
Mat3 bradford(const double from[2], const double to[2])
{
    const Mat3 b { { { 0.8951, 0.2664, -0.1614 }, { -0.7502, 1.7135, 0.0367 },
        { 0.0389, -0.0685, 1.0296 } } };
    const auto ws = xyzOf(from[0], from[1]), wd = xyzOf(to[0], to[1]);
    Mat3 scale {};
    for (int i = 0; i < 3; ++i) {
        double s = 0, d = 0;
        for (int k = 0; k < 3; ++k)
            s += b[i][k] * ws[k], d += b[i][k] * wd[k];
        scale[i][i] = d / s;
    }
    return mul(inverse(b), mul(scale, b));
}

const double kD65[2] = { 0.3127, 0.3290 };
const double kAcesWhite[2] = { 0.32168, 0.33767 };
const double kRec709[3][2] = { { 0.64, 0.33 }, { 0.30, 0.60 }, { 0.15, 0.06 } };
const double kAP0[3][2] = { { 0.7347, 0.2653 }, { 0.0, 1.0 }, { 0.0001, -0.0770 } };
const double kAP1[3][2] = { { 0.713, 0.293 }, { 0.165, 0.830 }, { 0.128, 0.044 } };

// Linear Rec.709 (D65) -> an ACES space (ACES white), Bradford adapted.
Mat3 rec709ToAces(const double prim[3][2])
{
    return mul(inverse(rgbToXyz(prim, kAcesWhite)),
        mul(bradford(kD65, kAcesWhite), rgbToXyz(kRec709, kD65)));
}

float displayed(const ColorManager& cm, float v, const std::string& view)
{
    float px[3] = { v, v, v };
    cm.toDisplay(px, 1, 1, 3, "", "", view);
    EXPECT_NEAR(px[0], px[1], 1e-5);
    EXPECT_NEAR(px[1], px[2], 1e-5);
    return px[0];
}

} // namespace

TEST(ColorConvert, DefaultConfigNamesAndDefaults)
{
    ColorManager cm;
    EXPECT_EQ(cm.config().reason, "afn default");
    EXPECT_EQ(cm.workingSpace(), "Linear Rec.709");
    EXPECT_EQ(cm.defaultDisplay(), "sRGB");
    EXPECT_EQ(cm.defaultView("sRGB"), "Standard");
    EXPECT_EQ(cm.defaultView(""), "Standard");
    const std::vector<std::string> views { "Standard", "Filmic (ACES SDR)", "Log", "Raw" };
    EXPECT_EQ(cm.views("sRGB"), views);
    EXPECT_EQ(cm.displays(), std::vector<std::string> { "sRGB" });
    for (const char* name : { "Linear Rec.709", "ACES2065-1", "ACEScg", "sRGB Texture",
             "Log2 Filmic", "Raw", "lin_rec709", "scene_linear", "data" })
        EXPECT_TRUE(cm.hasColorSpace(name)) << name;
    EXPECT_FALSE(cm.hasColorSpace("No Such Space"));
    EXPECT_FALSE(cm.hasColorSpace(""));
}

TEST(ColorConvert, StandardViewIsTheSrgbCurve)
{
    ColorManager cm;
    // 0.18 -> 1.055 * 0.18^(1/2.4) - 0.055 = 0.46135; default optimisation allows ~1e-4.
    EXPECT_NEAR(displayed(cm, 0.18f, "Standard"), srgbEncode(0.18), 2e-4);
    EXPECT_NEAR(displayed(cm, 0.18f, ""), srgbEncode(0.18), 2e-4);
    EXPECT_NEAR(displayed(cm, 0.001f, "Standard"), srgbEncode(0.001), 2e-4); // linear toe
    EXPECT_NEAR(displayed(cm, 0.0f, "Standard"), 0.0, 1e-5);
    // A non-grey colour: XYZ round trip is the identity, so each channel is just encoded.
    float px[3] = { 0.5f, 0.2f, 0.05f };
    cm.toDisplay(px, 1, 1, 3, "Linear Rec.709", "sRGB", "Standard");
    EXPECT_NEAR(px[0], srgbEncode(0.5), 3e-4);
    EXPECT_NEAR(px[1], srgbEncode(0.2), 3e-4);
    EXPECT_NEAR(px[2], srgbEncode(0.05), 3e-4);
}

TEST(ColorConvert, AcesSdrViewToneMapsMidGrey)
{
    ColorManager cm;
    // ACES 1.0: the RRT + ODT splines map scene 0.18 to 4.8 nit on a [0.02, 48] nit range; the
    // video ODT then applies the dim-surround gamma 0.9811 to Y, and the sRGB display encodes:
    // srgb(((4.8 - 0.02) / (48 - 0.02))^0.9811) = 0.35595.
    const double y = std::pow((4.8 - 0.02) / (48.0 - 0.02), 0.9811);
    EXPECT_NEAR(displayed(cm, 0.18f, "Filmic (ACES SDR)"), srgbEncode(y), 3e-4);
    // Tone mapping rolls off highlights: 16 stays below display white, and the curve is monotonic.
    const float hi = displayed(cm, 16.f, "Filmic (ACES SDR)");
    EXPECT_GT(hi, 0.99f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_LT(displayed(cm, 1.f, "Filmic (ACES SDR)"), hi);
    EXPECT_LT(displayed(cm, 0.18f, "Filmic (ACES SDR)"), displayed(cm, 1.f, "Filmic (ACES SDR)"));
}

TEST(ColorConvert, LogAndRawViews)
{
    ColorManager cm;
    // Log2 allocation over [-12.473931188, 12.526068812] stops: (log2(0.18) + 12.4739...) / 25.
    const double log018 = (std::log2(0.18) + 12.473931188) / 25.0;
    EXPECT_NEAR(log018, 0.4, 1e-6);
    EXPECT_NEAR(displayed(cm, 0.18f, "Log"), log018, 2e-4);
    EXPECT_NEAR(displayed(cm, 1.0f, "Log"), 12.473931188 / 25.0, 2e-4);
    EXPECT_FLOAT_EQ(displayed(cm, 0.18f, "Raw"), 0.18f);
    EXPECT_FLOAT_EQ(displayed(cm, 5.0f, "Raw"), 5.0f);
}

TEST(ColorConvert, LinearToAcesMatchesBradfordMatrices)
{
    ColorManager cm;
    const float in[3] = { 0.7f, 0.25f, 0.05f };
    for (const auto& [space, prim] :
        { std::pair<const char*, const double(*)[2]> { "ACES2065-1", kAP0 }, { "ACEScg", kAP1 } }) {
        const Mat3 m = rec709ToAces(prim);
        float px[3] = { in[0], in[1], in[2] };
        cm.convert(px, 1, 1, 3, "Linear Rec.709", space);
        for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(px[r], m[r][0] * in[0] + m[r][1] * in[1] + m[r][2] * in[2], 2e-6) << space;
        cm.toWorking(px, 1, 1, 3, space);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(px[c], in[c], 2e-6) << space;
    }
    // A known entry: Rec.709 red in ACES2065-1 is about (0.4396, 0.0898, 0.0175).
    float red[3] = { 1, 0, 0 };
    cm.convert(red, 1, 1, 3, "lin_rec709", "aces_interchange");
    EXPECT_NEAR(red[0], 0.4396, 1e-4);
    EXPECT_NEAR(red[1], 0.0898, 1e-4);
    EXPECT_NEAR(red[2], 0.0175, 1e-4);
}

TEST(ColorConvert, SrgbTextureDecodesAndRoundTrips)
{
    ColorManager cm;
    float px[6] = { 0.5f, 0.02f, 1.0f, 0.0f, 0.25f, 0.75f };
    const float enc[6] = { 0.5f, 0.02f, 1.0f, 0.0f, 0.25f, 0.75f };
    cm.toWorking(px, 2, 1, 3, "sRGB Texture");
    for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(px[i], srgbDecode(enc[i]), 1e-6) << i; // 0.5 -> 0.214041, 0.02 -> 0.001548
    const float lin[6] = { 0.f, 0.001f, 0.18f, 0.5f, 1.f, 4.f };
    float buf[6];
    std::copy(lin, lin + 6, buf);
    cm.convert(buf, 2, 1, 3, "Linear Rec.709", "sRGB Texture");
    for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(buf[i], srgbEncode(lin[i]), 1e-5) << i;
    cm.convert(buf, 2, 1, 3, "sRGB Texture", "Linear Rec.709");
    for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(buf[i], lin[i], 1e-5 * std::max(1.f, lin[i])) << i;
}

TEST(ColorConvert, StridedBufferTouchesOnlyRgb)
{
    ColorManager cm;
    const int w = 3, h = 2, stride = 5;
    std::vector<float> px(w * h * stride);
    for (int i = 0; i < w * h; ++i) {
        float* p = &px[i * stride];
        p[0] = 0.1f * (i + 1), p[1] = 0.05f * i, p[2] = 0.9f;
        p[3] = std::nanf(""), p[4] = -123.5f - i; // must survive untouched
    }
    const std::vector<float> before = px;
    cm.convert(px.data(), w, h, stride, "Linear Rec.709", "sRGB Texture");
    for (int i = 0; i < w * h; ++i) {
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(px[i * stride + c], srgbEncode(before[i * stride + c]), 1e-5);
        EXPECT_TRUE(std::isnan(px[i * stride + 3]));
        EXPECT_EQ(px[i * stride + 4], before[i * stride + 4]);
    }
    cm.toDisplay(px.data(), w, h, stride, "sRGB Texture", "sRGB", "Log");
    for (int i = 0; i < w * h; ++i) {
        EXPECT_TRUE(std::isnan(px[i * stride + 3]));
        EXPECT_EQ(px[i * stride + 4], before[i * stride + 4]);
    }
}

TEST(ColorConvert, UnknownNamesListTheValidOnes)
{
    ColorManager cm;
    float px[3] = { 0.5f, 0.5f, 0.5f };
    try {
        cm.convert(px, 1, 1, 3, "Linear Rec.709", "No Such Space");
        FAIL() << "expected ColorError";
    } catch (const ColorError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("No Such Space"), std::string::npos) << msg;
        EXPECT_NE(msg.find("ACEScg"), std::string::npos) << msg;
        EXPECT_NE(msg.find("config.ocio"), std::string::npos) << msg;
    }
    try {
        cm.toDisplay(px, 1, 1, 3, "", "sRGB", "Filmic");
        FAIL() << "expected ColorError";
    } catch (const ColorError& e) {
        EXPECT_NE(std::string(e.what()).find("Filmic (ACES SDR)"), std::string::npos) << e.what();
    }
    EXPECT_THROW(cm.toDisplay(px, 1, 1, 3, "", "P3", ""), ColorError);
    EXPECT_THROW(cm.views("P3"), ColorError);
    EXPECT_THROW(cm.convert(px, 1, 1, 2, "Raw", "Raw"), ColorError); // stride < 3
    EXPECT_THROW(cm.convert(nullptr, 1, 1, 3, "Raw", "Raw"), ColorError); // null buffer
    EXPECT_FLOAT_EQ(px[0], 0.5f);
}

TEST(ColorConvert, ConcurrentUseGivesSerialResults)
{
    ColorManager cm;
    const int n = 4096;
    std::vector<float> ref(n * 3);
    for (int i = 0; i < n * 3; ++i)
        ref[i] = float(i % 97) / 31.f;
    std::vector<float> serial = ref;
    cm.toDisplay(serial.data(), n, 1, 3, "", "sRGB", "Filmic (ACES SDR)");
    std::vector<std::vector<float>> outs(8, ref);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([&, t] {
            if (t % 2)
                cm.convert(outs[t].data(), n, 1, 3, "Linear Rec.709", "ACEScg");
            else
                cm.toDisplay(outs[t].data(), n, 1, 3, "", "sRGB", "Filmic (ACES SDR)");
        });
    for (auto& th : threads)
        th.join();
    for (int t = 0; t < 8; t += 2)
        EXPECT_EQ(outs[t], serial);
    for (int t = 3; t < 8; t += 2)
        EXPECT_EQ(outs[t], outs[1]);
}
