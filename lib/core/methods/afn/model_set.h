// SPDX-License-Identifier: Apache-2.0
// The trained AFN models a filter can choose from, one per input set (methods/afn/input_set.h),
// and the choice for a frame's inputs.
//
// Where they come from: the archives embedded at build time (lib/core/methods/afn/CMakeLists.txt:
// AFN_WEIGHTS_FILE, the full-input model, and AFN_INPUT_SET_WEIGHTS, one archive per further
// input set), or the one archive given with afnSetFilterData(filter, "weights", ...), which then
// replaces them all.
//
// The choice (fallback order): among the models whose input set the frame covers, the one that
// uses the most inputs; on a tie the one with the temporal branch in use, then one trained for
// exactly the inputs it uses, then the one listed first. Among the models for that same input set,
// the one trained at the sample count nearest the frame's (archive metadata `spp`, absent = 1;
// nearest in log2, a tie goes to the lower count; a frame of unknown count, spp 0, counts as 1
// spp). The frame inputs the chosen model was not trained for are not used (network_inputs.h:
// held at their neutral values) and the report says so. No covered model: an error naming the
// frame's inputs and the available sets, never a model run on inputs it was not trained for.
//
// A frame without a history (no motion vectors, no positions with a camera) is covered by a
// temporal model whose other inputs it has: the model runs single-frame, its TA input the frame's
// irradiance and its history input 1 (inputsToUse). That is exactly its input on the first frame
// of every training sequence, and after a history cut, so it was trained for it. Choice, measured
// on the held-out afn-v4 sequences without motion and positions (docs/afn-evaluation.md, "Frames
// without a history"): a 16-spp frame with albedo, normal and depth gains 2.3 dB on average from
// the 16-spp temporal model over the 1-spp single-frame one; at 1 spp the two are within 0.25 dB
// on every sequence (+0.05 on average).
#pragma once

#include "methods/afn/input_set.h"
#include "methods/afn/network.h"
#include "nn/weights.h"

#include <cstddef>
#include <string>
#include <vector>

namespace afn::afnet {

struct Model {
    InputSet inputs; ///< what it was trained for (the archive's `inputs` metadata)
    int spp = 1; ///< samples per pixel of its training inputs (the archive's `spp` metadata)
    Network net;
};

class ModelSet {
public:
    /// The archives built into the library (empty when the build embeds none).
    static ModelSet embedded();
    /// One archive given at run time; throws InvalidArgument for invalid data or `inputs`.
    static ModelSet fromData(const void* data, std::size_t size);

    /// Add the model of `archive` (its `inputs` metadata; none: the full set); throws
    /// InvalidArgument for an unknown input set or a graph that does not fit.
    void add(const nn::WeightsArchive& archive);

    bool empty() const { return m_models.empty(); }
    /// The model for a frame with `available` inputs and `spp` samples per pixel (0: unknown);
    /// nullptr when no model is covered. `allowLarge` false: AFN large is left out (an engine
    /// without its graph).
    Model* choose(const InputSet& available, int spp = 0, bool allowLarge = true);
    /// The models, e.g. "color; color+albedo+normal; color+albedo+normal (16 spp)" ("none" when
    /// empty; the count is named where it is not 1).
    std::string listing() const;
    /// The error for a frame with `available` inputs when choose() found nothing.
    [[noreturn]] void throwNoModelFor(const InputSet& available) const;

private:
    std::vector<Model> m_models;
};

/// The inputs `model` reads on a frame with `available` inputs: its own set, where a temporal
/// model on a frame without a history (no motion vectors, no positions with a camera) runs
/// single-frame: its TA input is the frame's irradiance and its history input 1, exactly its
/// input on the first frame of every training sequence.
InputSet inputsToUse(const InputSet& available, const Model& model);

/// What the afn method says about a frame's path (afntool --info and the per-frame log):
/// "model color+albedo+normal, single-frame (no temporal branch: no motion or position); not
/// used: depth"; a model trained at more than 1 spp is named with its count ("model
/// color+albedo+normal+depth+temporal (16 spp), temporal"), AFN large as such ("(64 spp, AFN
/// large)"; it reads no temporal accumulation even where its input set has the history).
std::string describeChoice(const InputSet& available, const Model& used);
/// The same for an input set alone (feature-only runs, where no model is chosen).
std::string describePath(const InputSet& available, const InputSet& used);

} // namespace afn::afnet
