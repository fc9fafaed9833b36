// SPDX-License-Identifier: Apache-2.0
// The AFN inference graph (training/afn/model.py is the definition; same tensor names):
//   x = [T(r_1spp), T(r_TA), albedo, normal01, depth01(, history01)] 13 (14) ch, full res (padded)
//   e1 = relu(enc1(D x)), e2 = relu(enc2(D e1)), e3 = relu(enc3(D e2))
//   d2 = relu(dec2([U e3, e2])), d1 = relu(dec1([U d2, e1]))          half-res-start U-Net
//   filtering + fusion (methods/afn/fusion.h) -> i
//   o = i + ref3(relu(ref2(relu(ref1([T(i), albedo, normal01, depth01])))))   variant "full" only
// with T(x) = clip(max(x, 0)^(1/2.2), 0, 1), D = 2x2 average pooling, U = nearest 2x upsampling.
// Odd sizes: every input is padded at the right/bottom to a multiple of 8 by edge replication,
// the graph runs on the padded frame and the output is cropped (same rule as PyTorch).
// Two paths compute the same graph, bit-identically:
// - run(): the production path, in horizontal stripes (network_stripes.cpp): each stripe of output
//   rows computes every layer over just the rows its receptive field needs, in a reusable stripe
//   workspace, so memory is O(stripe width x height), not O(frame), and no layer is stored at
//   frame size. It can skip stripes that a work mask does not ask for (work skipping).
// - runWholeFrame() = prepare, predict, filterAndFuse, refine, crop: every layer at frame size,
//   kept for the tests (the intermediates below) and the per-stage Google benchmark.
// The refinement runs in row strips with thread-local buffers in both (network_refine.cpp).
// Weights with quarter=1 (full and fusion only) add the quarter-resolution scale to filtering and
// fusion (quarter_scale.h): run() then computes them through runWholeFrame (no stripes, no work
// skipping, every row computed).
// Weights with history=1 (full and fusion only) add a 14th input channel, history01 (Inputs): the
// network sees how many frames its TA input holds at each pixel, so where the accumulation was
// reset (disocclusion, a lighting change cut by the history trust, the first frame) it can lean
// on the 1-spp branch and its spatial filtering (training/afn/model.py).
// Weights with albedoTrust=1 (full and fusion only) add the learned albedo trust
// (albedo_trust.h): a head on e1 predicts where to filter the colour itself instead of the
// albedo-demodulated colour; the output stays albedo-demodulated.
// Weights with variant=large hold AFN large, another graph (network_large.h): run() and
// runWholeFrame() then run it whole-frame, and the stage calls below are refused.
#pragma once

#include "base/image.h"
#include "methods/afn/albedo_trust.h"
#include "methods/afn/network_large.h"
#include "methods/afn/quarter_scale.h"
#include "methods/afn/tone_map.h"
#include "nn/conv.h"
#include "nn/weights.h"

#include <memory>
#include <string>

namespace afn::afnet {

/// Ablation variants (paper Table 11; training/afn/model.py) and AFN large (network_large.h).
enum class Variant { Full, Fusion, OneSpp, Ta, Large };

/// Network inputs, all W x H with the channel counts noted.
struct Inputs {
    const Image* color1 = nullptr; ///< 3 ch, 1-spp colour, albedo-demodulated linear HDR, >= 0
    const Image* colorTa = nullptr; ///< 3 ch, TA-1spp colour, demodulated linear HDR, >= 0
    const Image* albedo = nullptr; ///< 3 ch, [0, 1]
    const Image* normal01 = nullptr; ///< 3 ch, shading normal * 0.5 + 0.5, [0, 1]
    const Image* depth01 = nullptr; ///< 1 ch, per-frame min-max depth, [0, 1]
    /// 1 ch, 1 / (frames the TA input holds at the pixel), in [1/255, 1]: 1 where there is no
    /// history. Read only by weights with history=1 (Network::hasHistoryInput).
    const Image* history01 = nullptr;
};

/// Frame sizes are padded to a multiple of this (edge replication).
constexpr int kPadMultiple = 8;
inline int paddedSize(int n)
{
    return (n + kPadMultiple - 1) / kPadMultiple * kPadMultiple;
}

class Network {
public:
    /// Build the graph from an archive; throws "invalid or corrupted weights" on any mismatch.
    void load(const nn::WeightsArchive& weights);
    bool loaded() const { return m_loaded; }
    Variant variant() const { return m_variant; }
    /// Whether the weights add the quarter-resolution scale (quarter_scale.h).
    bool hasQuarterScale() const { return m_quarter; }
    /// Whether the weights take the history input history01 (a 14th input channel).
    bool hasHistoryInput() const { return m_history; }
    /// Whether the weights add the learned albedo trust (albedo_trust.h).
    bool hasAlbedoTrust() const { return m_albedoTrust; }
    /// Samples per pixel of the inputs the weights were trained at (archive metadata `spp`, 1
    /// when absent).
    int trainedSpp() const { return m_trainedSpp; }
    /// Channels of the network input x: 13, or 14 with the history input.
    int inputChannels() const { return m_history ? 14 : 13; }
    /// Run the convolutions in `p` from now on (nn::Conv::setPrecision; Fp32 after load): every
    /// layer of kernel prediction and refinement. In bf16 the input tone map (toneMapRunBf16) and
    /// the softmax's exponential (cpu/afn_filter_avx512.cpp) take cheaper approximations; the 7x7
    /// filtering and the fusion stay fp32. AFN large runs fp32 whatever `p`.
    void setPrecision(nn::Precision p);
    /// What the convolutions run in (Fp32 for AFN large).
    nn::Precision precision() const { return m_precision; }

    /// Whole forward pass in stripes: `out` = o (3 ch, demodulated, W x H, not clamped).
    /// `work` (W x H, 1 ch, or null/empty = everywhere): only the 8-row blocks that hold a
    /// non-zero pixel there are computed (runs of such blocks cut into stripes); the other rows
    /// take the cheap path, `out` = in.colorTa (the temporal accumulation, the input colour where
    /// there is no history). Computed rows are bit-identical to a run without mask (work=0 pixels
    /// in them included). AFN large computes every row whatever the mask.
    void run(const Inputs& in, Image& out, const Image* work = nullptr);
    /// The same result through the whole-frame stages; keeps the intermediates below.
    void runWholeFrame(const Inputs& in, Image& out);
    /// Rows of the frame (of H) the last run()'s work mask left to the cheap path, and the
    /// stripes it computed.
    int skippedRows() const { return m_skippedRows; }
    int stripes() const { return m_stripes; }
    /// Input rows of the last run() that a stripe took over from the previous stripe's window
    /// instead of computing them again (network_stripes.cpp).
    int inputRowsReused() const { return m_inputRowsReused; }

    // The stages, callable one by one (benchmark): prepare + predict = kernel prediction.
    // Not for AFN large (prepare() throws InvalidOperation).
    void prepare(const Inputs& in); ///< pad, tone map, build x and D(r_1spp)
    void predict(); ///< encoder-decoder up to d1
    void filterAndFuse(); ///< heads, softmax, filtering, fusion (and the quarter scale)
    void refine(); ///< refinement (copy of i when the variant has none)
    void crop(Image& out) const; ///< o cropped to the input size
    /// The fused image i as output (no refinement: quality_tiers.h's fast tier), cropped to the
    /// input size, in the albedo-demodulated space (the albedo trust undone).
    void fusedToOutput(Image& out) const;

    /// The stages as timed by run() (the benchmark's and afntool's GFLOP/s).
    enum class Stage { Prediction, Filtering, Refinement };
    static constexpr int kStages = 3;
    static const char* stageName(Stage s); ///< "prediction", "filtering", "refinement"
    /// FLOP of `s` for one frame at the last run's size: 2 x multiply-adds of its conv layers and
    /// 7x7 filters over the padded pixels they compute (softmax, pooling, tone map not counted).
    double stageFlop(Stage s) const;
    /// Wall-clock milliseconds of `s` in the last run(). In stripes the stages interleave across
    /// threads: the run's wall time is split in proportion to the thread time each stage took.
    double stageMs(Stage s) const { return m_stageMs[static_cast<int>(s)]; }
    /// Of stageMs(Prediction), the part that prepares the network input and does no FLOP: the
    /// tone map, the 13-channel input and the colours (fillInput) and the 1-spp colour's pooling.
    /// Split from the wall time like the stages. 0 where not measured (AFN large).
    double predictionInputMs() const { return m_inputMs; }

    /// The layers, for engines that pack them in their own layout (lib/core/cuda).
    enum class Layer { Enc1, Enc2, Enc3, Dec2, Dec1, Head1, HeadTa, Ref1, Ref2, Ref3 };
    const nn::Conv& layer(Layer which) const;
    /// The albedo trust's head headG (hasAlbedoTrust() only; else not loaded).
    const nn::Conv& albedoTrustHead() const { return m_headG; }

    /// Intermediates at the padded size (tests) of the last runWholeFrame() or stage calls:
    /// network input x, fused i, d_TA, alpha; the decoder output d1 and d_1spp at half size.
    const Image& input() const { return m_x; }
    const Image& decoderOutput() const { return m_d1; }
    const Image& fused() const { return m_fused; }
    const Image& filteredTa() const { return m_dTa; }
    const Image& alpha() const { return m_alpha; }
    const Image& filtered1Half() const { return m_d1Half; }
    /// The albedo trust's colour-space share t at half size (hasAlbedoTrust() only).
    const Image& albedoTrust() const { return m_trust; }
    /// The quarter scale's intermediates (hasQuarterScale() only).
    const QuarterBuffers& quarter() const { return m_quarterBuf; }
    /// The quarter scale's head head4 (hasQuarterScale() only; else not loaded).
    const nn::Conv& quarterHead() const { return m_head4; }
    /// AFN large's graph and its intermediates (variant Large only).
    const LargeNetwork& large() const { return m_large; }

private:
    struct StripeWorkspace; // network_stripes.cpp
    /// Rows [y0, y1) of the padded frame into x, color1, colorTa (13 or 14, 3, 3 ch), whose row 0
    /// is padded row `origin` (edge replication of the W x H inputs, tone map of x's colours).
    void fillInput(const Inputs& in, int y0, int y1, int origin, Image& x, Image& color1,
        Image& colorTa) const;
    /// Refined rows [y0, y1) of `fused` (3 ch) with the features of `x` (13-14 ch, same rows):
    /// o row y at dst + (y - y0) * dstRow, width x 3 floats. Rows outside the images read zero.
    void refineRows(
        const Image& fused, const Image& x, int y0, int y1, float* dst, long dstRow) const;
    /// The tone map of the inputs that only the convolutions read (x's colours, the refinement's
    /// input): toneMapRunBf16 where they run in bf16 (which rounds its inputs next), else
    /// toneMapRun.
    void toneMapNetworkInput(const float* in, float* out, int n) const;
    struct WorkspacePool; // network_stripes.cpp
    /// Output rows [y0, y1) of the padded frame (cropped into `out`); adds each stage's thread
    /// milliseconds to ms[] and, of the prediction's, the input preparation's to *inputMs.
    /// `runId` identifies the run() (its inputs), for the input rows `ws` may still hold.
    void runStripe(const Inputs& in, int y0, int y1, StripeWorkspace& ws, Image& out, double* ms,
        double* inputMs, std::uint64_t runId, int* rowsReused) const;
    /// The inputs with the variant's substitution applied, shapes checked; sets the size.
    Inputs checkInputs(const Inputs& in);

    bool m_loaded = false;
    bool m_quarter = false; ///< hasQuarterScale()
    bool m_history = false; ///< hasHistoryInput()
    bool m_albedoTrust = false; ///< hasAlbedoTrust()
    int m_trainedSpp = 1; ///< trainedSpp()
    nn::Precision m_precision = nn::Precision::Fp32; ///< precision()
    int m_skippedRows = 0, m_stripes = 0, m_inputRowsReused = 0;
    Variant m_variant = Variant::Full;
    nn::Conv m_enc1, m_enc2, m_enc3, m_dec2, m_dec1, m_head1, m_headTa, m_ref1, m_ref2, m_ref3;
    nn::Conv m_head4; ///< the quarter scale's head (hasQuarterScale() only)
    nn::Conv m_headG; ///< the albedo trust's head (hasAlbedoTrust() only)
    QuarterBuffers m_quarterBuf;
    int m_width = 0, m_height = 0;
    double m_stageMs[kStages] = {};
    double m_inputMs = 0.0; ///< predictionInputMs()
    // Buffers, reused across frames of one size.
    Image m_x, m_colorTa, m_color1, m_color1Half, m_xHalf, m_e1, m_e1Pool, m_e2, m_e2Pool, m_e3;
    Image m_d2, m_d1, m_fused, m_dTa, m_alpha, m_d1Half, m_out, m_trust;
    // Stripe workspaces of run(), reused across frames; copies of the Network share them (a
    // cache behind a mutex).
    std::shared_ptr<WorkspacePool> m_pool;
    LargeNetwork m_large; ///< the graph of variant Large
};

} // namespace afn::afnet
