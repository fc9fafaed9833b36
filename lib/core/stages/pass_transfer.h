// SPDX-License-Identifier: Apache-2.0
// Light-path passes denoised with the beauty, consistently with it (docs/passes.md).
//
// Every method's output B' is a denoised beauty. The beauty is a sum of terms, B = sum_i P_i x F_i
// (+ R), with P_i a light pass, F_i its colour factor (Blender's DiffCol; 1 for passes without one)
// and R what the bound passes do not hold (about 0 when every pass is bound and they add up). With
// A ONE linear filter, the same weights for every image -- an edge-aware a-trous (5x5 B3-spline
// taps, steps 1, 2, 4, 8; weights from the denoised beauty's luminance difference relative to the
// centre pixel's, the normals' cosine^16 and the relative depth difference the method was given),
// then an exponential history (alpha 0.2, reprojected with the method's own taps, cut by its
// history trust) -- the denoised passes are
//     P_i' = A(P_i) x g,   g = B' / D,   D = sum_i A(P_i) x F_i + A(R)   (per pixel and channel),
// so that sum_i P_i' x F_i + A(R) x g = B' exactly: with every pass bound, the denoised passes
// rebuild the denoised beauty by the renderer's own formula, whatever the method did (its network,
// kernels, refinement, post-filter, TAA are carried over through g). Each pass gets the beauty's
// detail (edges, texture) through B' and the factor, and its own smooth share A(P_i) F_i / D of it.
// The light passes are filtered before the factor (demodulated): light is smooth across the
// texture edges of the factor, and a pass whose factor is 0 at a pixel still gets a denoised value
// there (it adds nothing to the beauty).
//
// Choice: this is one stage for every method (ta, svgf, bmfr, afn, the learned baselines), rather
// than each method's own per-pixel kernels applied to each pass: the methods' last steps are not
// linear (afn's refinement, the post-filter, TAA clamping), and a share carried through g keeps
// the sum exact where re-running them per pass would not. Where D is 0 (no sample in the filter's
// reach found light) but B' is not, B' goes to the first bound pass (by name) whose factor there is
// at least 0.01 (or that has none). Colour factors are not denoised (albedo-like).
#pragma once

#include "base/image.h"
#include "stages/history_trust.h"
#include "stages/reproject.h"

#include <map>
#include <string>
#include <vector>

namespace afn {

/// One pass to denoise: its input, optional colour factor and output (caller's buffers).
struct PassBinding {
    std::string name;
    ImageView light; ///< the light pass P (>= 3 channels)
    ImageView factor; ///< its colour factor F (>= 3 channels), empty = 1
    ImageView output; ///< where P' goes (>= 3 channels; a 4th is set to 1)
};

/// What the transfer reads besides the passes (caller's buffers; optional ones may be empty).
struct PassGuides {
    ImageView beauty; ///< the noisy beauty B (>= 3 channels)
    ImageView denoised; ///< the method's output B' (>= 3 channels)
    ImageView normal; ///< unit normals (any space), optional
    ImageView depth; ///< linear depth, optional
    /// The method's taps into the previous frame (nullptr or !hasHistory(): no history).
    const Reprojector* reprojector = nullptr;
    const HistoryTrust* trust = nullptr; ///< the method's history trust, optional
};

class PassTransfer {
public:
    /// Denoise `passes` for one frame; keeps the filtered stack as the next frame's history.
    void run(const PassGuides& guides, const std::vector<PassBinding>& passes);
    void reset()
    {
        m_history = Image();
        m_names.clear();
    }

    /// a-trous steps and the history's blend factor (see the file comment).
    static constexpr int kLevels = 4;
    static constexpr float kAlpha = 0.2f;

private:
    void filterSpatial(const PassGuides& guides, int channels);
    void accumulate(const PassGuides& guides, bool useHistory);

    Image m_stack; ///< R then every P_i, 3 channels each
    Image m_scratch;
    Image m_guide; ///< luminance of B', normal xyz, depth, their scales (pass_transfer.cpp)
    Image m_history; ///< last frame's accumulated stack
    std::vector<std::string> m_names; ///< passes of the history, in stack order
};

} // namespace afn
