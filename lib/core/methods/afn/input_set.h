// SPDX-License-Identifier: Apache-2.0
// Input sets of the afn method: which auxiliary inputs a frame brings, and which a
// trained model was trained for. The colour is always there; the optional parts are albedo,
// normal, depth and a temporal history. A frame has a history when it has motion vectors, or world
// positions with a camera (stages/reproject.cpp); without either it runs in single-frame mode.
//
// Choices (written down here, see also docs/afn-evaluation.md):
// - An .afnw archive names its input set in the metadata key `inputs` (training/afn/weights.py):
//   "color" or a comma list of albedo, normal, depth, temporal, e.g. "albedo,normal". An archive
//   without the key is the full set "albedo,normal,depth,temporal" (every archive written before
//   input sets existed, and the shipped weights/afn.afnw).
// - The network keeps its 13 inputs for every set: a role the model was not trained for is held
//   at its neutral constant (albedo 1 = no demodulation, normal01 0.5, depth01 0), exactly as in
//   its training data (afntool --aov ROLE=none). Nothing is estimated from the colour.
// - Single-frame mode (a model without `temporal`): the TA branch input is the current frame's
//   irradiance (no temporal accumulation reaches the network), in training and in use.
#pragma once

#include <string>

namespace afn {
struct Frame;
}

namespace afn::afnet {

struct InputSet {
    bool albedo = false;
    bool normal = false;
    bool depth = false;
    bool temporal = false;

    /// The set every archive without an `inputs` key was trained for.
    static InputSet full() { return { true, true, true, true }; }
    bool operator==(const InputSet& o) const
    {
        return albedo == o.albedo && normal == o.normal && depth == o.depth
            && temporal == o.temporal;
    }
    /// True when every input of `required` is in this set.
    bool covers(const InputSet& required) const;
    /// Number of optional inputs (the model choice prefers the largest covered set).
    int count() const;
};

/// The inputs `frame` brings.
InputSet inputSetOf(const Frame& frame);

/// "color", "color+albedo+normal", ..., "color+albedo+normal+depth+temporal".
std::string inputSetName(const InputSet& set);

/// The metadata spelling: "color" or "albedo,normal,depth,temporal" (a subset, in that order).
std::string inputSetKey(const InputSet& set);

/// Parse the metadata spelling (order-free, "color" optional); false on an unknown word.
bool parseInputSet(const std::string& text, InputSet& set);

} // namespace afn::afnet
