// SPDX-License-Identifier: Apache-2.0
// The quality tier high (methods/afn/quality_tiers.h: a self-ensemble over the flips the network
// was trained with) on the CUDA engine: per pass (flipX, flipY) = none, x, y, both, the network's
// inputs mirrored (flipPixel), the network run on them writing its demodulated output
// (FinalOutput::demodulated), that output mirrored back and added (addPassPixel), and at the end
// the sum times 1/4 remodulated as the network's output is (averagePassesPixel): the CPU's
// TierRunner::runHigh() in its order of additions.
#pragma once

#include "cuda/conv_tile.h"

#include <cstddef>

namespace afn::cuda {

constexpr int kHighTierPasses = 4;
/// Channels of the network's frame-size sources in their order (AfnPipeline::NetworkSources:
/// color1, colorTa, albedo, normal, depth, historyLength), each mirrored for a pass.
constexpr int kNetworkSourceChannels[6] = { 3, 3, 3, 3, 1, 1 };

/// dst(x, y) = src(x', y') of a `channels`-channel frame, x' = w - 1 - x where fx, y' likewise.
AFN_HD void flipPixel(
    const float* src, float* dst, int channels, int w, int h, int x, int y, bool fx, bool fy)
{
    const std::size_t d = static_cast<std::size_t>(y) * w + x;
    const std::size_t s = static_cast<std::size_t>(fy ? h - 1 - y : y) * w + (fx ? w - 1 - x : x);
    for (int c = 0; c < channels; ++c)
        dst[channels * d + c] = src[channels * s + c];
}

/// sum(x, y) += pass(x', y') (3 channels; the first pass adds to 0, as the CPU's zero-filled sum).
AFN_HD void addPassPixel(
    const float* pass, float* sum, int w, int h, int x, int y, bool fx, bool fy, bool first)
{
    const std::size_t d = static_cast<std::size_t>(y) * w + x;
    const std::size_t s = static_cast<std::size_t>(fy ? h - 1 - y : y) * w + (fx ? w - 1 - x : x);
    for (int c = 0; c < 3; ++c)
        sum[3 * d + c] = (first ? 0.0f : sum[3 * d + c]) + pass[3 * s + c];
}

/// The output at (x, y): the passes' mean, remodulated (`out` without trust or skipping).
AFN_HD void averagePassesPixel(const float* sum, const FinalOutput& out, int x, int y)
{
    const std::size_t p = static_cast<std::size_t>(y) * out.width + x;
    for (int c = 0; c < 3; ++c)
        out.data[3 * p + c] = outputValue(out, x, y, c, sum[3 * p + c] * (1.0f / kHighTierPasses));
}

} // namespace afn::cuda
