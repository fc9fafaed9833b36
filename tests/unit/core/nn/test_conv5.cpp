// SPDX-License-Identifier: Apache-2.0
// nn::Conv with 5x5 kernels (WSKPN, NBGD) against a scalar reference, on both kernel families
// (portable and, where the CPU has it, AVX-512), with widths that are not multiples of the lanes,
// an odd frame (borders on every side) and the implicit-upsampling input; runRows over whole rows
// and over column chunks gives the same bits.
#include "afn_test_util.h"
#include "cpu/isa.h"
#include "isa_scope.h"
#include "nn/conv.h"

#include <gtest/gtest.h>

#include <algorithm>

using afn::Image;

namespace {

using isa_test::IsaScope;

using afntest::randomImage;
using afntest::randomVec;

/// Scalar 5x5 convolution, zero padding 2, of concat(U(up), same), in double.
double reference(const Image* up, const Image& same, const std::vector<float>& wt,
    const std::vector<float>& bias, int cin, int x, int y, int o)
{
    const int cu = up ? up->channels() : 0;
    double acc = bias[o];
    for (int ci = 0; ci < cin; ++ci)
        for (int ky = 0; ky < 5; ++ky)
            for (int kx = 0; kx < 5; ++kx) {
                const int xx = x + kx - 2, yy = y + ky - 2;
                if (xx < 0 || yy < 0 || xx >= same.width() || yy >= same.height())
                    continue;
                const float v = ci < cu ? (*up)(xx / 2, yy / 2, ci) : same(xx, yy, ci - cu);
                acc += v * wt[((static_cast<std::size_t>(o) * cin + ci) * 5 + ky) * 5 + kx];
            }
    return acc;
}

/// Forces an ISA for its lifetime and restores the one before.
void checkConv5(afn::cpu::Isa isa, int cu, int cs, int co, int w, int h, bool relu)
{
    const IsaScope scope(isa);
    const int cin = cu + cs;
    const auto wt = randomVec(static_cast<std::size_t>(co) * cin * 25, 11);
    const auto bias = randomVec(co, 12);
    afn::nn::Conv conv;
    conv.load(
        afntest::parseArchive(
            { { "c.weight",
                  { static_cast<std::uint32_t>(co), static_cast<std::uint32_t>(cin), 5, 5 }, wt },
                { "c.bias", { static_cast<std::uint32_t>(co) }, bias } }),
        "c", cin);
    EXPECT_EQ(conv.kernelSize(), 5);
    EXPECT_DOUBLE_EQ(conv.flopPerPixel(), 2.0 * 25 * cin * co);
    const Image up = randomImage((w + 1) / 2, (h + 1) / 2, std::max(cu, 1), 13);
    const Image same = randomImage(w, h, cs, 14);
    Image out;
    conv.run(cu ? &up : nullptr, same, out, relu);
    ASSERT_EQ(out.channels(), co);
    double worst = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int o = 0; o < co; ++o) {
                double want = reference(cu ? &up : nullptr, same, wt, bias, cin, x, y, o);
                if (relu)
                    want = std::max(want, 0.0);
                worst = std::max(worst, std::abs(out(x, y, o) - want));
            }
    EXPECT_LT(worst, 2e-5) << afn::cpu::isaName(isa) << " cin " << cin << " cout " << co;
    // runRows writes the same values into a caller buffer (a wider pixel stride).
    std::vector<float> rows(static_cast<std::size_t>(h) * w * (co + 3), -7.0f);
    conv.runRows(
        cu ? &up : nullptr, same, 0, h, rows.data(), static_cast<long>(w) * (co + 3), co + 3, relu);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int o = 0; o < co; ++o)
                ASSERT_EQ(rows[(static_cast<std::size_t>(y) * w + x) * (co + 3) + o], out(x, y, o));
    // Column ranges (the AFN heads' chunks): chunks of 1, 4 and 7 columns, each written from
    // dst = its first column, give every value of the whole rows, bit for bit: the halo columns
    // are read from the input, the zero padding only at the frame's border.
    for (int chunk : { 1, 4, 7 }) {
        std::vector<float> part(static_cast<std::size_t>(h) * chunk * co, -7.0f);
        for (int x0 = 0; x0 < w; x0 += chunk) {
            const int x1 = std::min(w, x0 + chunk);
            conv.runRows(cu ? &up : nullptr, same, 0, h, part.data(), static_cast<long>(chunk) * co,
                co, relu, x0, x1);
            for (int y = 0; y < h; ++y)
                for (int x = x0; x < x1; ++x)
                    for (int o = 0; o < co; ++o)
                        ASSERT_EQ(part[(static_cast<std::size_t>(y) * chunk + x - x0) * co + o],
                            out(x, y, o))
                            << "chunk " << chunk << " at " << x << "," << y;
        }
    }
}

} // namespace

TEST(Conv5, PortableMatchesScalarReference)
{
    checkConv5(afn::cpu::Isa::Portable, 0, 10, 14, 23, 9, false); // WSKPN's first layer
    checkConv5(afn::cpu::Isa::Portable, 0, 14, 12, 17, 6, true);
    checkConv5(afn::cpu::Isa::Portable, 3, 2, 5, 9, 7, true); // upsampled input
}

TEST(Conv5, Avx512MatchesScalarReference)
{
    // On a CPU without AVX-512F forceIsa keeps the portable kernels: the test still checks them.
    checkConv5(afn::cpu::Isa::Avx512, 0, 10, 20, 23, 9, false); // NBGD's guide network
    checkConv5(afn::cpu::Isa::Avx512, 0, 20, 5, 31, 5, true);
    checkConv5(afn::cpu::Isa::Avx512, 0, 14, 14, 37, 11, true);
    checkConv5(afn::cpu::Isa::Avx512, 3, 2, 17, 9, 7, false);
    // At most 4 outputs: input channels in the lanes (cpu/conv_avx512.cpp rowsFewOutputs).
    checkConv5(afn::cpu::Isa::Avx512, 0, 16, 3, 21, 6, false); // as the refinement's last layer
    checkConv5(afn::cpu::Isa::Avx512, 3, 2, 1, 9, 7, true); // upsampled input, one output
    checkConv5(afn::cpu::Isa::Avx512, 0, 20, 4, 17, 5, true); // two groups of 16 channels
    checkConv5(afn::cpu::Isa::Avx512, 0, 7, 2, 5, 3, false);
}
