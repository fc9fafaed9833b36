// SPDX-License-Identifier: Apache-2.0
// The per-frame constants of the CUDA engine from a gathered frame and the filter's settings
// (plain C++: also used by the host emulation of the kernels in the tests).
#pragma once

#include "cuda/highlight_pixel.h"
#include "cuda/temporal_pixel.h"
#include "filter/frame.h"
#include "stages/aux_prefilter.h"
#include "stages/highlight_bypass.h"
#include "stages/history_trust.h"
#include "stages/reproject.h"
#include "stages/temporal_accumulation.h"

#include <algorithm>

namespace afn::cuda {

static_assert(FrameConstants {}.highlights == kHighlightFactor, "the highlight bypass's default");
static_assert(cuda::kHighlightStride == afn::kHighlightStride, "the highlight limit's sample");

inline FrameConstants frameConstants(const Frame& in, const ReprojectSettings& reproject,
    const AccumulationSettings& accumulation, const HistoryTrustSettings& trust,
    const AuxSettings& aux)
{
    FrameConstants c;
    c.hasHistory = in.frameIndex > 0 ? 1 : 0;
    c.useCamera = in.camera.valid && in.prevCamera.valid ? 1 : 0;
    std::copy(in.prevCamera.viewProjection.begin(), in.prevCamera.viewProjection.end(),
        c.prevViewProjection);
    c.pixelOffset[0] = in.camera.pixelOffset[0];
    c.pixelOffset[1] = in.camera.pixelOffset[1];
    c.positionLimit = reproject.positionLimit;
    c.positionLimitSquared = reproject.positionLimitSquared;
    c.normalLimitSquared = reproject.normalLimitSquared;
    c.depthLimit = reproject.depthLimit;
    c.alphaMin = accumulation.alphaMin;
    c.antilag = trust.antilag;
    c.auxMode = aux.aux == AuxSettings::Mode::Clean ? 1
        : aux.aux == AuxSettings::Mode::Noisy       ? 2
                                                    : 0;
    c.spp = aux.spp;
    c.colorDemodulated = in.colorDemodulated ? 1 : 0;
    return c;
}

} // namespace afn::cuda
