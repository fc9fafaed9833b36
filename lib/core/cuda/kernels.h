// SPDX-License-Identifier: Apache-2.0
// Launchers of the CUDA engine's kernels (one .cu file each), callable from plain C++. Each
// enqueues its kernel on `stream` (also while the stream is being captured into a graph) and
// throws afn::Exception when the launch is refused.
//
// Per frame, in stream order (afn_pipeline.cpp):
//   auxPrefilter                       flags, decision, prefiltered normal, depth and albedo
//   resetFrameCounters, temporal       TA: demodulate, reproject, history trust, accumulate;
//                                      depth range
//   (undemodulate)                     the colours again times the albedo, for a model
//                                      without albedo on a frame with one
//   prepare                            network input x, its 2 x 2 average, D(1-spp colour)
//   conv / pool                        encoder-decoder at 1/2 .. 1/8 resolution (tensor cores)
//   albedoTrust                        after the first encoder level: t, the colours times s
//                                      (weights with albedoTrust=1)
//   filterFuse                         heads, softmax, 7 x 7 filtering, Eq. 3
//   (quarter=1: down2 x 2, convLinear, quarterDelta, addUpsampled4, refineInput or fusedOutput)
//   conv x 3 (the last: convFinal)     refinement, residual, remodulation, crop
//   AFN large instead of prepare .. convFinal (large_graph.h): largePrepare, down2, the U-Net,
//   convLinear (3 heads), largeFilter (3 scales), fuseScales x 2, largeRefineInput and conv x 3
//   per refinement module
//   (quality=high: flip, the network, addPass per pass; averagePasses)
//   taa                                the output TAA (its output is the next frame's history)
//   postFilter                         guides, six half-passes of the a-trous smoothing
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

#include <cuda_runtime_api.h>

namespace afn::cuda {

/// The aux prefilter over the frame (aux_prefilter_pixel.h): `t` the frame's temporal buffers,
/// whose normal and depth are b.normalOut and b.depthOut.
void launchAuxPrefilter(const AuxBuffers& b, const TemporalBuffers& t, const FrameConstants* frame,
    cudaStream_t stream);

/// Set the depth-range keys (2 words: min, max) to the empty range and the cut pixel count to 0.
void launchResetFrameCounters(std::uint32_t* depthRange, unsigned* cutPixels, cudaStream_t stream);

/// First stage over the frame (gather, history trust, blend); also folds valid depths into
/// `depthRange` (when there is depth) and adds the trust's cut pixels to t.cutPixels.
void launchTemporal(const TemporalBuffers& b, const TrustBuffers& t, const FrameConstants* frame,
    std::uint32_t* depthRange, cudaStream_t stream);

/// Network input over the half-resolution grid of the padded frame.
void launchPrepare(const PrepareBuffers& b, cudaStream_t stream);

/// `out` = undemodulateValue(`irradiance`, `albedo`) (3 floats per pixel of a w x h frame): the
/// colours a model without albedo filters when the frame has one (network_inputs.h).
void launchUndemodulate(const float* irradiance, const float* albedo, bool plain, float* out, int w,
    int h, cudaStream_t stream);

/// afn's highlight bypass (highlight_pixel.h): the limit of `ta` (3 floats per pixel) into
/// *limit (device memory), through the histogram `counts` (kHighlightBins words, zeroed here).
void launchHighlightLimit(const float* ta, int width, int height, const FrameConstants* frame,
    unsigned* counts, float* limit, cudaStream_t stream);
/// `out` = `in` clamped at *limit (3 floats per pixel).
void launchHighlightClamp(
    const float* in, const float* limit, float* out, int width, int height, cudaStream_t stream);
/// `out` (3 floats per pixel) += the excess of `ta` over *limit times the albedo factor.
void launchHighlightExcess(const float* ta, const float* albedo, bool plain, const float* limit,
    float* out, int width, int height, cudaStream_t stream);

/// D: 2 x 2 average of a half-precision NHWC tensor (`stride` halves per pixel, even size) into
/// `out` of half the size and the same stride.
void launchPool(const std::uint16_t* in, int width, int height, int stride, std::uint16_t* out,
    cudaStream_t stream);

/// The albedo trust over the half-resolution grid of the padded frame.
void launchAlbedoTrust(const AlbedoTrustBuffers& b, cudaStream_t stream);

/// A hidden convolution layer (bias, ReLU, half-precision output).
void launchConvRelu(const ConvOperands& op, const ReluOutput& out, cudaStream_t stream);

/// A layer without activation (AFN large's heads), float output.
void launchConvLinear(const ConvOperands& op, const LinearOutput& out, cudaStream_t stream);

/// The last refinement layer (3 output channels), writing the remodulated, cropped output.
void launchConvFinal(const ConvOperands& op, const FinalOutput& out, cudaStream_t stream);

/// Heads, softmax, filtering and Eq. 3 over the padded frame.
void launchFilterFuse(const FilterFuseArgs& a, cudaStream_t stream);

/// AFN large (large_pixel.h): the input preparation over the half-resolution grid of the padded
/// frame; D of a float image (`out` w x h, `in` twice that); one scale's softmax and 5 x 5
/// filtering; Eq. 3 between scales in place on `fine` (width x height); a refinement module's
/// input over the padded frame (width x height).
void launchLargePrepare(const LargePrepareBuffers& b, cudaStream_t stream);
void launchDown2(const float* in, float* out, int w, int h, int channels, cudaStream_t stream);
void launchLargeFilter(const LargeFilterArgs& a, cudaStream_t stream);
void launchFuseScales(float* fine, const float* coarse, const float* logits, int logitStride,
    int channel, int width, int height, cudaStream_t stream);
void launchLargeRefineInput(const float* o, const std::uint16_t* x, std::uint16_t* refineInput,
    int width, int height, cudaStream_t stream);

/// AFN's quarter-resolution scale (quarter_pixel.h): delta at 1/4 of the padded size; i +=
/// U4(delta) over the padded frame (width x height); then the refinement input from i over the
/// padded frame, or the output from i (no refinement) over the frame.
void launchQuarterDelta(const QuarterArgs& a, cudaStream_t stream);
void launchAddUpsampled4(
    const float* delta, float* fused, int width, int height, cudaStream_t stream);
void launchRefineInput(const float* fused, const std::uint16_t* x, std::uint16_t* refineInput,
    int width, int height, cudaStream_t stream);
void launchFusedOutput(
    const float* fused, int paddedWidth, const FinalOutput& out, cudaStream_t stream);

/// afn's output TAA over the frame; `t` the frame's temporal buffers (for the history taps),
/// `trust` the history trust's (read where it was measured).
void launchTaa(const TaaBuffers& a, const TemporalBuffers& t, const TrustBuffers& trust,
    const FrameConstants* frame, cudaStream_t stream);

/// afn's post-filter of `in` into `out` (frame size, 3 floats per pixel; `out` may be `in`): the
/// guides into `g` (s.maxSamples from frame->alphaMin), the half-passes through `scratch0` and
/// `scratch1` (frame size, 3 floats per pixel each).
void launchPostFilter(const PostFilterSources& s, const PostFilterPlanes& g,
    const FrameConstants* frame, const float* in, float* out, float* scratch0, float* scratch1,
    cudaStream_t stream);

/// The quality tier high: `dst` = `src` mirrored (`channels` floats per pixel of a w x h frame);
/// `sum` += `pass` mirrored back (`first`: sum = 0 + pass); the output = the mean of the passes
/// in `sum`, remodulated (high_tier_pixel.h).
void launchFlip(const float* src, float* dst, int channels, int w, int h, bool fx, bool fy,
    cudaStream_t stream);
void launchAddPass(
    const float* pass, float* sum, int w, int h, bool fx, bool fy, bool first, cudaStream_t stream);
void launchAveragePasses(const float* sum, const FinalOutput& out, cudaStream_t stream);

} // namespace afn::cuda
