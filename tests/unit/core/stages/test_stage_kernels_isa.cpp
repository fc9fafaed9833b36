// SPDX-License-Identifier: Apache-2.0
// The AVX-512 pre-tests of the shared stages (stages/aux_noise_avx512.cpp: speckle estimate;
// stages/reproject_avx512.cpp: a static camera's rows; stages/demodulate_avx512.cpp) settle only
// what the scalar tests would decide the same way: flags, counts and taps are identical to the
// portable path's, on buffers wide enough for several 16-pixel blocks and a tail, with the values
// that need care (NaN, inf, -0, sky depth, zero normals, moved positions); the demodulation's
// kernels give the scalar loops' bits. On a CPU without AVX-512F both runs take the portable path
// and the test checks nothing beyond it (said in the output).
#include "cpu/isa.h"
#include "isa_scope.h"
#include "stages/aux_noise.h"
#include "stages/demodulate.h"
#include "stages/reproject.h"
#include "test_methods_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <vector>

namespace {

using isa_test::haveAvx512;
using isa_test::IsaScope;

using afn::Frame;
using afn::Image;
using afn::cpu::Isa;
using methods_test::Lcg;

constexpr int W = 53, H = 9; // 3 blocks of 16 after column 0, and a tail

/// A buffer of `channels` that is mostly smooth (constant runs), with speckle, NaN, inf, -0 and
/// (depth) sky pixels sprinkled in.
Image testBuffer(int channels, afn::AuxKind kind, std::uint32_t seed)
{
    Lcg rng { seed };
    Image img(W, H, channels);
    const float inf = std::numeric_limits<float>::infinity();
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float r = rng.next();
            for (int c = 0; c < channels; ++c) {
                float v = kind == afn::AuxKind::Depth ? 5.0f + 0.01f * (x / 7)
                                                      : 0.3f + 0.1f * c + 0.02f * (x / 9);
                if (r > 0.6f)
                    v += 0.5f * std::fabs(rng.next()); // speckle
                else if (r < -0.97f)
                    v = std::numeric_limits<float>::quiet_NaN();
                else if (r < -0.94f)
                    v = c == 0 ? inf : -inf;
                else if (r < -0.90f)
                    v = -0.0f;
                else if (r < -0.85f && kind == afn::AuxKind::Depth)
                    v = 1e10f; // sky
                img(x, y, c) = v;
            }
        }
    return img;
}

TEST(StageKernelsIsa, SpeckleFlagsAndCountsMatchThePortablePath)
{
    if (!haveAvx512())
        std::cout << "no AVX-512F on this CPU: both runs are portable\n";
    const std::pair<afn::AuxKind, int> kinds[]
        = { { afn::AuxKind::Albedo, 3 }, { afn::AuxKind::Normal, 3 }, { afn::AuxKind::Depth, 1 } };
    for (const auto& [kind, channels] : kinds)
        for (std::uint32_t seed : { 1u, 2u, 3u }) {
            const Image img = testBuffer(channels, kind, seed);
            Image flagsV, flagsP;
            std::int64_t nV, nP, cV, cP;
            {
                IsaScope s(Isa::Avx512);
                nV = afn::speckleFlags(img.view(), kind, flagsV);
                cV = afn::speckleCount(img.view(), kind);
            }
            {
                IsaScope s(Isa::Portable);
                nP = afn::speckleFlags(img.view(), kind, flagsP);
                cP = afn::speckleCount(img.view(), kind);
            }
            EXPECT_EQ(nV, nP);
            EXPECT_EQ(cV, cP);
            EXPECT_EQ(cP, nP);
            EXPECT_GT(nP, 0); // the buffer has speckle and clean pixels
            EXPECT_LT(nP, static_cast<std::int64_t>(W) * H / 2);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x)
                    EXPECT_EQ(flagsV(x, y, 0), flagsP(x, y, 0))
                        << "kind " << static_cast<int>(kind) << " seed " << seed << " at " << x
                        << "," << y;
        }
}

/// A static frame: positions on a plane, some moved by the seed, normals partly zero.
Frame staticFrame(std::uint32_t seed)
{
    Lcg rng { seed };
    Frame f;
    f.width = W;
    f.height = H;
    f.color = Image(W, H, 3, 1.0f);
    f.position = Image(W, H, 3);
    f.normal = Image(W, H, 3);
    f.motion = Image(W, H, 2, 0.0f); // zero motion: identity rows
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float r = rng.next();
            f.position(x, y, 0) = 0.1f * x;
            f.position(x, y, 1) = 0.1f * y;
            f.position(x, y, 2) = r > 0.7f ? 0.02f * r : (r < -0.95f ? 5.0f : 0.0f);
            const bool zero = r < -0.9f && r >= -0.95f;
            f.normal(x, y, 2) = zero ? 0.0f : 1.0f;
            f.normal(x, y, 0)
                = r > 0.4f && r <= 0.7f ? 0.8f * r : 0.0f; // some fail the normal test
        }
    return f;
}

TEST(StageKernelsIsa, StaticRowTapsMatchThePortablePath)
{
    for (bool box : { false, true }) {
        afn::ReprojectSettings s;
        s.boxFallback = box;
        const Frame prev = staticFrame(7u), cur = staticFrame(8u);
        afn::Reprojector v, p;
        v.setSettings(s);
        p.setSettings(s);
        v.storeGeometry(prev);
        p.storeGeometry(prev);
        {
            IsaScope scope(Isa::Avx512);
            v.compute(cur);
        }
        {
            IsaScope scope(Isa::Portable);
            p.compute(cur);
        }
        int accepted = 0, rejected = 0;
        for (int y = 0; y < H; ++y) {
            ASSERT_TRUE(v.identityRow(y));
            for (int x = 0; x < W; ++x) {
                const afn::PixelTaps a = v.taps(x, y), b = p.taps(x, y);
                EXPECT_EQ(a.mask, b.mask) << x << "," << y << " box " << box;
                EXPECT_EQ(a.box, b.box) << x << "," << y;
                EXPECT_EQ(a.onScreen, b.onScreen) << x << "," << y;
                EXPECT_EQ(a.x0, b.x0) << x << "," << y;
                EXPECT_EQ(a.y0, b.y0) << x << "," << y;
                for (int k = 0; k < 4; ++k)
                    EXPECT_EQ(a.w[k], b.w[k]) << x << "," << y;
                EXPECT_EQ(v.ownPixelAccepted(x, y), b.mask == 1 && !b.box);
                accepted += b.mask != 0;
                rejected += b.mask == 0;
            }
        }
        EXPECT_GT(accepted, 0);
        EXPECT_GT(rejected, 0);
    }
}

} // namespace

TEST(StageKernelsIsa, DemodulationAndRemodulationMatchThePortablePath)
{
    // stages/demodulate_avx512.cpp against the scalar loops: colour and albedo with NaN, +-inf,
    // -0, negative, tiny (below the 2^-10 floor) and huge values (above kMaxIrradiance after the
    // division), with and without an albedo, for colour given as radiance and as irradiance; and
    // rows remodulated into a caller's buffer (streaming stores) at every alignment.
    auto awkward = [](std::uint32_t seed) {
        Lcg rng { seed };
        Image img(W, H, 3);
        const float inf = std::numeric_limits<float>::infinity();
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float r = rng.next();
                    img(x, y, c) = r < -0.9f ? std::numeric_limits<float>::quiet_NaN()
                        : r < -0.8f          ? (r < -0.85f ? inf : -inf)
                        : r < -0.7f          ? -0.0f
                        : r < -0.6f          ? -0.25f * std::fabs(rng.next())
                        : r < -0.5f          ? 1e-6f * std::fabs(rng.next())
                        : r > 0.9f           ? 1e13f * (1.0f + std::fabs(rng.next()))
                                             : std::fabs(rng.next());
                }
        return img;
    };
    const Image color = awkward(31u), albedo = awkward(32u), filtered = awkward(33u);
    auto bitsOf = [](float v) {
        std::uint32_t u;
        std::memcpy(&u, &v, sizeof u);
        return u;
    };
    int compared = 0;
    for (bool withAlbedo : { true, false })
        for (bool demodulatedInput : { false, true }) {
            Frame f;
            f.width = W;
            f.height = H;
            f.color = color;
            if (withAlbedo)
                f.albedo = albedo;
            f.colorDemodulated = demodulatedInput;
            Image irrV, irrP, radV, radP;
            {
                IsaScope s(Isa::Avx512);
                afn::demodulate(f, irrV);
                afn::remodulate(f, filtered, radV);
            }
            {
                IsaScope s(Isa::Portable);
                afn::demodulate(f, irrP);
                afn::remodulate(f, filtered, radP);
            }
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x)
                    for (int c = 0; c < 3; ++c) {
                        ASSERT_EQ(bitsOf(irrV(x, y, c)), bitsOf(irrP(x, y, c)))
                            << "demodulated at " << x << "," << y << " channel " << c << " albedo "
                            << withAlbedo << " irradiance input " << demodulatedInput;
                        ASSERT_EQ(bitsOf(radV(x, y, c)), bitsOf(radP(x, y, c)))
                            << "remodulated at " << x << "," << y << " channel " << c << " albedo "
                            << withAlbedo << " irradiance input " << demodulatedInput;
                        ++compared;
                    }
            // Rows written to a caller's buffer (streaming stores past the first 64-byte
            // boundary), at every float offset within a cache line: the same bits, and nothing
            // written before or after the row.
            for (int offset = 0; offset < 16; ++offset) {
                std::vector<float> buf(3 * W + 48, -3.0f);
                float* out = buf.data() + offset;
                const IsaScope s(Isa::Avx512);
                for (int y = 0; y < H; ++y) {
                    afn::remodulateRow(
                        f, filtered, y, reinterpret_cast<std::byte*>(out), 3 * sizeof(float), true);
                    for (int k = 0; k < 3 * W; ++k)
                        ASSERT_EQ(bitsOf(out[k]), bitsOf(radP.at(0, y)[k]))
                            << "caller row " << y << " value " << k << " offset " << offset;
                    for (int k = 0; k < offset; ++k)
                        ASSERT_EQ(buf[k], -3.0f);
                    for (std::size_t k = offset + 3 * W; k < buf.size(); ++k)
                        ASSERT_EQ(buf[k], -3.0f);
                }
            }
        }
    EXPECT_EQ(compared, 4 * W * H * 3);
}
