// SPDX-License-Identifier: Apache-2.0
// large.cu's and quarter.cu's kernels on the CPU (see cuda_emulator.h): the per-block and
// per-pixel code of large_pixel.h and quarter_pixel.h over the kernels' grids.
#include "cuda_emulator.h"

#include <cstddef>

namespace afntest {

using namespace afn::cuda;

void emulateLargePrepare(const LargePrepareBuffers& b)
{
    const DepthScale ds = b.depth ? depthScale(b.depthRange[0], b.depthRange[1]) : DepthScale {};
    for (int yh = 0; yh < b.paddedHeight / 2; ++yh)
        for (int xh = 0; xh < b.paddedWidth / 2; ++xh)
            largePrepareBlock(b, ds, xh, yh);
}

void emulateDown2(const float* in, float* out, int w, int h, int channels)
{
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            down2Pixel(in, out, w, channels, x, y);
}

void emulateLargeFilter(const LargeFilterArgs& a)
{
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            largeFilterPixel(a, x, y);
}

void emulateFuseScales(float* fine, const float* coarse, const float* logits, int logitStride,
    int channel, int width, int height)
{
    for (int cy = 0; cy < height / 2; ++cy)
        for (int cx = 0; cx < width / 2; ++cx)
            fuseScalesBlock(fine, coarse, logits, logitStride, channel, width, cx, cy);
}

void emulateLargeRefineInput(
    const float* o, const std::uint16_t* x, std::uint16_t* refineInput, int width, int height)
{
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p)
        largeRefineInputPixel(o, x, refineInput, p);
}

void emulateQuarterDelta(const QuarterArgs& a)
{
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            quarterDeltaPixel(a, x, y);
}

void emulateAddUpsampled4(const float* delta, float* fused, int width, int height)
{
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            addUpsampled4Pixel(delta, fused, width, height, x, y);
}

void emulateRefineInput(
    const float* fused, const std::uint16_t* x, std::uint16_t* refineInput, int width, int height)
{
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p)
        refineInputPixel(fused, x, refineInput, p);
}

void emulateFusedOutput(const float* fused, int paddedWidth, const FinalOutput& out)
{
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            fusedOutputPixel(fused, paddedWidth, out, x, y);
}

} // namespace afntest
