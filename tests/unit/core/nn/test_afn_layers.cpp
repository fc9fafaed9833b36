// SPDX-License-Identifier: Apache-2.0
// AFN building blocks against naive references and hand cases: conv (with the implicit nearest
// upsampling input), pooling, softmax, the 7x7 kernel apply, and Eq. 3 through the fused pass.
#include "afn_test_util.h"
#include "base/exception.h"
#include "methods/afn/fusion.h"
#include "methods/afn/network.h"
#include "nn/conv.h"

#include <gtest/gtest.h>

#include <cmath>

using afn::Image;
using afntest::NamedTensor;

namespace {

using afntest::randomImage;
using afntest::randomVec;

} // namespace

TEST(AfnLayers, ConvMatchesNaiveReferenceWithUpsampledInput)
{
    const int cu = 3, cs = 2, co = 5, w = 6, h = 4;
    const auto wt = randomVec(co * (cu + cs) * 9, 1), bias = randomVec(co, 2);
    afn::nn::Conv conv;
    conv.load(afntest::parseArchive(
                  { { "c.weight", { co, cu + cs, 3, 3 }, wt }, { "c.bias", { co }, bias } }),
        "c", cu + cs);
    const Image up = randomImage(w / 2, h / 2, cu, 3), same = randomImage(w, h, cs, 4);
    Image out;
    conv.run(&up, same, out, true);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int o = 0; o < co; ++o) {
                double acc = bias[o];
                for (int ci = 0; ci < cu + cs; ++ci)
                    for (int ky = 0; ky < 3; ++ky)
                        for (int kx = 0; kx < 3; ++kx) {
                            const int xx = x + kx - 1, yy = y + ky - 1;
                            if (xx < 0 || yy < 0 || xx >= w || yy >= h)
                                continue;
                            const float v
                                = ci < cu ? up(xx / 2, yy / 2, ci) : same(xx, yy, ci - cu);
                            acc += v * wt[((o * (cu + cs) + ci) * 3 + ky) * 3 + kx];
                        }
                EXPECT_NEAR(out(x, y, o), std::max(acc, 0.0), 1e-5) << x << "," << y << "," << o;
            }
}

TEST(AfnLayers, ConvRejectsInconsistentShapes)
{
    const auto a = afntest::parseArchive({ { "c.weight", { 4, 2, 3, 3 }, randomVec(72, 1) },
        { "c.bias", { 3 }, randomVec(3, 2) }, { "d.weight", { 4, 2, 7, 7 }, randomVec(392, 1) },
        { "d.bias", { 4 }, randomVec(4, 2) } });
    afn::nn::Conv conv;
    EXPECT_THROW(conv.load(a, "c", 2), afn::Exception); // bias size
    EXPECT_THROW(conv.load(a, "d", 2), afn::Exception); // 7x7 (1, 3 and 5 are supported)
    EXPECT_THROW(conv.load(a, "e", 2), afn::Exception); // missing
}

TEST(AfnLayers, Down2AndSoftmax)
{
    Image in(2, 2, 1);
    in(0, 0, 0) = 1;
    in(1, 0, 0) = 2;
    in(0, 1, 0) = 3;
    in(1, 1, 0) = 6;
    Image out;
    afn::nn::down2(in, out);
    EXPECT_EQ(out(0, 0, 0), 3.0f);
    float v[49];
    for (int j = 0; j < 49; ++j)
        v[j] = j == 10 ? 1e30f : -1e30f;
    afn::afnet::softmax(v, 49);
    EXPECT_EQ(v[10], 1.0f);
    EXPECT_EQ(v[0], 0.0f);
    float u[3] = { 0.0f, std::log(2.0f), std::log(5.0f) }; // 1 : 2 : 5
    afn::afnet::softmax(u, 3);
    EXPECT_NEAR(u[0], 1.0 / 8, 1e-7);
    EXPECT_NEAR(u[2], 5.0 / 8, 1e-7);
}

TEST(AfnLayers, Down2IsTheWindowSumInRowOrderOverFour)
{
    // PyTorch's avg_pool2d order, bit for bit, for 3, 13, 16 and 37 channels.
    for (const int c : { 3, 13, 16, 37 }) {
        const Image in = randomImage(10, 6, c, 17u + static_cast<unsigned>(c));
        Image out;
        afn::nn::down2(in, out);
        ASSERT_EQ(out.width(), 5);
        ASSERT_EQ(out.height(), 3);
        int differ = 0;
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 5; ++x)
                for (int k = 0; k < c; ++k) {
                    const float want = (in(2 * x, 2 * y, k) + in(2 * x + 1, 2 * y, k)
                                           + in(2 * x, 2 * y + 1, k) + in(2 * x + 1, 2 * y + 1, k))
                        / 4.0f;
                    differ += out(x, y, k) != want;
                }
        EXPECT_EQ(differ, 0) << c << " channels";
    }
}

TEST(AfnLayers, KernelApplyIdentityShiftAndBorder)
{
    const Image img = randomImage(9, 8, 3, 5);
    float k[49] = {}, rgb[3];
    k[24] = 1.0f; // centre
    afn::afnet::applyKernel(img, 4, 4, k, rgb);
    EXPECT_EQ(rgb[1], img(4, 4, 1));
    k[24] = 0.0f;
    k[3 * 7 + 4] = 1.0f; // dx = +1
    afn::afnet::applyKernel(img, 8, 3, k, rgb); // right border: reads outside -> 0
    EXPECT_EQ(rgb[0], 0.0f);
    afn::afnet::applyKernel(img, 0, 0, k, rgb);
    EXPECT_EQ(rgb[2], img(1, 0, 2));
    for (float& f : k)
        f = 1.0f / 49; // box at the corner: 16 of 49 taps inside, no renormalisation
    afn::afnet::applyKernel(img, 0, 0, k, rgb);
    double s = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            s += img(x, y, 0);
    EXPECT_NEAR(rgb[0], s / 49, 1e-6);
}

TEST(AfnLayers, FusionEq3HandCase)
{
    // Heads with zero weights and biases that make both kernels the identity (centre tap) and
    // alpha = sigmoid(0) = 0.5: then d_TA = r_TA, d_1spp = D(r_1spp) and
    // i = r_TA - 0.5 * mean_block(r_TA) + 0.5 * D(r_1spp).
    const int cd = 2;
    std::vector<float> b1(49, -1e4f), bt(50, -1e4f);
    b1[24] = 0.0f;
    bt[24] = 0.0f;
    bt[49] = 0.0f;
    const auto a = afntest::parseArchive(
        { { "h1.weight", { 49, cd, 1, 1 }, std::vector<float>(49 * cd, 0.0f) },
            { "h1.bias", { 49 }, b1 },
            { "ht.weight", { 50, cd + 13, 1, 1 }, std::vector<float>(50 * 15, 0.0f) },
            { "ht.bias", { 50 }, bt } });
    afn::nn::Conv h1, ht;
    h1.load(a, "h1", cd, 49);
    ht.load(a, "ht", cd + 13, 50);
    const Image d1 = randomImage(2, 1, cd, 6), x = randomImage(4, 2, 13, 7);
    Image ta(4, 2, 3), c1(4, 2, 3);
    const float block[4] = { 1, 2, 3, 6 }; // mean 3
    for (int bx = 0; bx < 2; ++bx)
        for (int q = 0; q < 4; ++q)
            for (int c = 0; c < 3; ++c) {
                ta(2 * bx + (q & 1), q >> 1, c) = block[q] * (1 + bx + c);
                c1(2 * bx + (q & 1), q >> 1, c) = 5.0f * (1 + bx + c); // D(c1) = 5 (1 + bx + c)
            }
    Image c1h, fused, dta, alpha, d1h;
    afn::nn::down2(c1, c1h);
    afn::afnet::FusionInputs in { &d1, &x, &ta, &c1h, &h1, &ht };
    afn::afnet::filterAndFuse(in, { &fused, &dta, &alpha, &d1h });
    for (int bx = 0; bx < 2; ++bx)
        for (int q = 0; q < 4; ++q)
            for (int c = 0; c < 3; ++c) {
                const float s = static_cast<float>(1 + bx + c);
                EXPECT_EQ(alpha(2 * bx + (q & 1), q >> 1, 0), 0.5f);
                EXPECT_FLOAT_EQ(fused(2 * bx + (q & 1), q >> 1, c), (block[q] - 1.5f + 2.5f) * s);
            }
}

TEST(AfnLayers, ToneMap)
{
    EXPECT_EQ(afn::afnet::toneMap(-1.0f), 0.0f);
    EXPECT_EQ(afn::afnet::toneMap(7.0f), 1.0f);
    EXPECT_NEAR(afn::afnet::toneMap(std::pow(0.5f, 2.2f)), 0.5f, 1e-6);
}
