// SPDX-License-Identifier: Apache-2.0
// The trained AFN models a filter can choose from, one per input set (methods/afn/input_set.h),
// and the choice for a frame's inputs (issue 19).
//
// Where they come from: the archives embedded at build time (lib/core/methods/afn/CMakeLists.txt:
// AFN_WEIGHTS_FILE, the full-input model, and AFN_INPUT_SET_WEIGHTS, one archive per further
// input set), or the one archive given with afnSetFilterData(filter, "weights", ...), which then
// replaces them all.
//
// The choice (fallback order): among the models whose input set the frame covers, the one with
// the most inputs; on a tie the one with the temporal branch, then the one listed first. The frame
// inputs the chosen model was not trained for are not used (network_inputs.h: held at their neutral
// values) and the report says so. No covered model: an error naming the frame's inputs and the
// available sets, never a model run on inputs it was not trained for.
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
    /// The model for a frame with `available` inputs; nullptr when no model is covered.
    Model* choose(const InputSet& available);
    /// The input sets of the models, e.g. "color; color+albedo+normal" ("none" when empty).
    std::string listing() const;
    /// The error for a frame with `available` inputs when choose() found nothing.
    [[noreturn]] void throwNoModelFor(const InputSet& available) const;

private:
    std::vector<Model> m_models;
};

/// What the afn method says about a frame's path (afntool --info and the per-frame log):
/// "color+albedo+normal, single-frame (no motion or position: no temporal branch); model
/// color+albedo+normal; not used: depth".
std::string describePath(const InputSet& available, const InputSet& used);

} // namespace afn::afnet
