// SPDX-License-Identifier: Apache-2.0
// The CUDA afn engine run on the CPU, for machines without a GPU: the kernels' own per-pixel,
// per-block and per-lane code (lib/core/cuda/*_pixel.h, *_block.h, conv_tile.h,
// filter_fuse_lane.h) driven by plain loops over warps and lanes, with the tensor-core instruction
// and the quad shuffles emulated from their PTX definitions (independently of fragment.h). It
// wires the stages exactly as cuda/afn_pipeline.cpp does, so its results are what the GPU
// computes up to the order of the tensor cores' float additions; the tests compare it with the
// CPU engine to check the kernels' index math and to measure the half-precision error.
#pragma once

#include "base/image.h"
#include "cuda/conv_tile.h"
#include "cuda/filter_fuse_lane.h"
#include "cuda/prepare_block.h"
#include "cuda/temporal_pixel.h"
#include "filter/frame.h"
#include "methods/afn/network.h"

#include <array>
#include <cstdint>
#include <vector>

namespace afntest {

/// c[lane] += A * B for mma.m16n8k16 (f16 inputs, f32 accumulation), A, B and C given as the 32
/// lanes' registers, laid out as the PTX ISA defines.
void emulateMma(
    const std::uint32_t (&a)[32][4], const std::uint32_t (&b)[32][2], float (&c)[32][4]);

/// The kernels of kernels.h on the CPU (same arguments, host pointers).
void emulateTemporal(const afn::cuda::TemporalBuffers& b, const afn::cuda::FrameConstants& f,
    std::uint32_t* depthRange);
void emulatePrepare(const afn::cuda::PrepareBuffers& b);
void emulatePool(const std::uint16_t* in, int width, int height, int stride, std::uint16_t* out);
void emulateConvRelu(const afn::cuda::ConvOperands& op, const afn::cuda::ReluOutput& out);
void emulateConvFinal(const afn::cuda::ConvOperands& op, const afn::cuda::FinalOutput& out);
void emulateFilterFuse(const afn::cuda::FilterFuseArgs& a);

/// The whole CUDA afn filter on the CPU (cuda/afn_pipeline.cpp's wiring, host buffers).
class EmulatedAfnPipeline {
public:
    explicit EmulatedAfnPipeline(const afn::afnet::Network& network);
    /// Denoise a gathered frame (as AfnCudaFilter::denoise) into `out` (3 ch, frame size).
    void run(const afn::Frame& frame, const afn::cuda::FrameConstants& constants, afn::Image& out);

    // Intermediates of the last frame, as floats.
    const afn::Image& irradiance() const { return m_irradianceImage; }
    const afn::Image& accumulated() const { return m_accumulatedImage; }
    afn::Image networkInput() const; ///< padded size, 13 ch
    afn::Image decoderOutput() const; ///< half the padded size

private:
    struct Tensor {
        std::vector<std::uint16_t> data;
        int width = 0, height = 0, stride = 0;
        void allocate(int w, int h, int channels);
        afn::Image toImage(int channels) const;
    };
    struct Layer {
        afn::cuda::PackedConv packed;
    };
    afn::cuda::ConvOperands operands(
        const Layer& layer, const Tensor* up, const Tensor& same) const;
    void allocate(const afn::Frame& frame);

    afn::afnet::Variant m_variant;
    bool m_refine;
    std::array<Layer, 10> m_layers;
    int m_width = 0, m_height = 0, m_paddedWidth = 0, m_paddedHeight = 0;
    int m_slot = 0;
    std::vector<float> m_color, m_albedo, m_motion, m_irradiance, m_output, m_color1Half, m_fused;
    std::array<std::vector<float>, 2> m_position, m_normal, m_depth, m_accumulated, m_history;
    Tensor m_x, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3, m_d2, m_d1, m_refineInput, m_r1,
        m_r2;
    afn::Image m_irradianceImage, m_accumulatedImage;
};

} // namespace afntest
