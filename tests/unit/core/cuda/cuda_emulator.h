// SPDX-License-Identifier: Apache-2.0
// The CUDA afn kernels run on the CPU, for machines without a GPU: the kernels' own per-pixel,
// per-block and per-lane code (lib/core/cuda/*_pixel.h, *_block.h, conv_tile.h,
// filter_fuse_lane.h) driven by plain loops over warps and lanes, with the tensor-core instruction
// and the quad shuffles emulated from their PTX definitions (independently of fragment.h).
// emulated_pipeline.h wires them as cuda/afn_pipeline.cpp does; the tests compare it with the
// CPU engine to check the kernels' index math and to measure the half-precision error.
#pragma once

#include "cuda/albedo_trust_block.h"
#include "cuda/aux_prefilter_pixel.h"
#include "cuda/conv_tile.h"
#include "cuda/filter_fuse_lane.h"
#include "cuda/high_tier_pixel.h"
#include "cuda/highlight_pixel.h"
#include "cuda/large_pixel.h"
#include "cuda/post_filter_pixel.h"
#include "cuda/prepare_block.h"
#include "cuda/quarter_pixel.h"
#include "cuda/taa_pixel.h"
#include "cuda/temporal_pixel.h"

#include <cstdint>

namespace afntest {

/// c[lane] += A * B for mma.m16n8k16 (f16 inputs, f32 accumulation), A, B and C given as the 32
/// lanes' registers, laid out as the PTX ISA defines.
void emulateMma(
    const std::uint32_t (&a)[32][4], const std::uint32_t (&b)[32][2], float (&c)[32][4]);

/// The kernels of kernels.h on the CPU (same arguments, host pointers).
/// aux_prefilter.cu's kernels in their order (the counts added without atomics).
void emulateAuxPrefilter(const afn::cuda::AuxBuffers& b, const afn::cuda::TemporalBuffers& t,
    const afn::cuda::FrameConstants& f);
/// temporal.cu's kernels in their order: gather (and depth range), the history trust's row sums,
/// launchHighlightLimit: the limit of `ta` (3 floats per pixel), the histogram's atomic
/// additions in any order (here row by row).
float emulateHighlightLimit(const float* ta, int w, int h, float factor);
/// launchHighlightClamp.
void emulateHighlightClamp(const float* in, float limit, float* out, int w, int h);
/// launchHighlightExcess.
void emulateHighlightExcess(
    const float* ta, const float* albedo, bool plain, float limit, float* out, int w, int h);
/// groups and soft minimum (adding to *t.cutPixels), blend.
void emulateTemporal(const afn::cuda::TemporalBuffers& b, const afn::cuda::TrustBuffers& t,
    const afn::cuda::FrameConstants& f, std::uint32_t* depthRange);
void emulateUndemodulate(
    const float* irradiance, const float* albedo, bool plain, float* out, int w, int h);
void emulatePrepare(const afn::cuda::PrepareBuffers& b);
void emulateAlbedoTrust(const afn::cuda::AlbedoTrustBuffers& b);
void emulatePool(const std::uint16_t* in, int width, int height, int stride, std::uint16_t* out);
void emulateConvRelu(const afn::cuda::ConvOperands& op, const afn::cuda::ReluOutput& out);
void emulateConvFinal(const afn::cuda::ConvOperands& op, const afn::cuda::FinalOutput& out);
void emulateConvLinear(const afn::cuda::ConvOperands& op, const afn::cuda::LinearOutput& out);
void emulateFilterFuse(const afn::cuda::FilterFuseArgs& a);
/// quarter.cu's kernels (cuda_emulator_scales.cpp).
void emulateQuarterDelta(const afn::cuda::QuarterArgs& a);
void emulateAddUpsampled4(const float* delta, float* fused, int width, int height);
void emulateRefineInput(
    const float* fused, const std::uint16_t* x, std::uint16_t* refineInput, int width, int height);
void emulateFusedOutput(const float* fused, int paddedWidth, const afn::cuda::FinalOutput& out);
/// large.cu's kernels (cuda_emulator_scales.cpp).
void emulateLargePrepare(const afn::cuda::LargePrepareBuffers& b);
void emulateDown2(const float* in, float* out, int w, int h, int channels);
void emulateLargeFilter(const afn::cuda::LargeFilterArgs& a);
void emulateFuseScales(float* fine, const float* coarse, const float* logits, int logitStride,
    int channel, int width, int height);
void emulateLargeRefineInput(
    const float* o, const std::uint16_t* x, std::uint16_t* refineInput, int width, int height);
/// high_tier.cu's kernels.
void emulateFlip(const float* src, float* dst, int channels, int w, int h, bool fx, bool fy);
void emulateAddPass(const float* pass, float* sum, int w, int h, bool fx, bool fy, bool first);
void emulateAveragePasses(const float* sum, const afn::cuda::FinalOutput& out);
/// taa.cu's kernel; `trust` null where the history trust was not measured.
void emulateTaa(const afn::cuda::TaaBuffers& a, const afn::cuda::TemporalBuffers& t,
    const afn::cuda::TrustBuffers* trust, const afn::cuda::FrameConstants& f);
/// post_filter.cu's kernels in their order (s.maxSamples as given): `in` into `out`.
void emulatePostFilter(const afn::cuda::PostFilterSources& s, const afn::cuda::PostFilterPlanes& g,
    const float* in, float* out, float* scratch0, float* scratch1);

} // namespace afntest
