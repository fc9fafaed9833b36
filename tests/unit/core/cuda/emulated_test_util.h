// SPDX-License-Identifier: Apache-2.0
// What the tests of the CUDA engine's host emulation share (test_cuda_emulated*.cpp): the test
// archives, the settings of the CPU stages they compare with, sequences with noisy AOVs.
#pragma once

#include "afn_parity_cases.h"
#include "afn_test_util.h"
#include "stages/aux_prefilter.h"
#include "stages/history_trust.h"
#include "stages/reproject.h"
#include "stages/temporal_accumulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace afntest {

inline std::vector<char> testWeights(const char* name)
{
    const auto bytes = readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/" + name);
    EXPECT_FALSE(bytes.empty()) << name;
    return bytes;
}

inline std::vector<char> shippedWeights(const char* name = "afn.afnw")
{
    return readBytes(std::string(AFN_SOURCE_DIR) + "/weights/" + name);
}

inline const afn::ReprojectSettings kReproject {};
inline const afn::AccumulationSettings kAccumulation {};
inline const afn::HistoryTrustSettings kTrust {}; ///< the default, antilag 1
inline const afn::AuxSettings kAux {}; ///< the default, auto at an unknown sample count

/// Frame k of `seq` with 1-spp-like noise in its auxiliary buffers inside a rectangle (an object
/// whose AOVs follow random specular bounces): each pixel's albedo scaled by a factor in
/// [0.2, 1.8], its normal tilted by up to 0.6 per axis (renormalised), its depth moved by up to
/// 10 %.
inline SequenceFrame noisyAovFrame(
    const SyntheticSequence& seq, int k, const SequenceInputs& inputs)
{
    SequenceFrame in = seq.frame(k, inputs);
    std::mt19937 rng(100u + static_cast<unsigned>(k));
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const int w = in.color.width(), h = in.color.height();
    for (int y = h / 4; y < 3 * h / 4; ++y)
        for (int x = w / 4; x < w / 2; ++x) {
            const float scale = 0.2f + 1.6f * u(rng);
            if (!in.albedo.empty())
                for (int c = 0; c < 3; ++c)
                    in.albedo(x, y, c) *= scale;
            float n[3], len2 = 0.0f;
            for (int c = 0; c < 3; ++c) {
                n[c] = 0.6f * (2.0f * u(rng) - 1.0f)
                    + (in.normal.empty() ? 0.0f : in.normal(x, y, c));
                len2 += n[c] * n[c];
            }
            if (!in.normal.empty() && len2 > 0.0f)
                for (int c = 0; c < 3; ++c)
                    in.normal(x, y, c) = n[c] / std::sqrt(len2);
            const float dz = 1.0f + 0.2f * (u(rng) - 0.5f);
            if (!in.depth.empty() && in.depth(x, y, 0) < 1e9f)
                in.depth(x, y, 0) *= dz;
        }
    return in;
}

/// Frame k of `seq` with its left half 3x brighter from frame 3 on (a light switched on there).
inline SequenceFrame lightSwitchedOnFrame(
    const SyntheticSequence& seq, int k, const SequenceInputs& inputs)
{
    SequenceFrame in = seq.frame(k, inputs);
    if (k >= 3)
        for (int y = 0; y < in.color.height(); ++y)
            for (int x = 0; x < in.color.width() / 2; ++x)
                for (int c = 0; c < 3; ++c)
                    in.color(x, y, c) *= 3.0f;
    return in;
}

inline bool sameBits(const afn::Image& a, const afn::Image& b)
{
    return a.size() == b.size()
        && (a.size() == 0 || std::memcmp(a.data(), b.data(), 4 * a.size()) == 0);
}

} // namespace afntest
