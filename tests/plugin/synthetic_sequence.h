// SPDX-License-Identifier: Apache-2.0
// A small synthetic render sequence for the plugin tests (no files, no other engineers' data):
// a smooth image with seeded multiplicative noise translated by whole pixels every frame, with
// matching albedo, normal, depth and to-previous motion in Blender's y-up pixel convention.
#pragma once

#include "ofx_test_host.h"

#include <string>
#include <vector>

namespace ofxtest {

struct Sequence {
    int width = 40, height = 24; ///< full-resolution size (even)
    int originX = 10, originY = -6; ///< canonical origin of the region of definition (even)
    int firstFrame = 1, numFrames = 6;
    int velocityX = 2, velocityY = 1; ///< content motion per frame, pixels, x right, y down

    /// Channels per role: color 4 (RGBA), albedo 4, normal 3, depth 1, position 3, motion 4 (x, y,
    /// 0, 0).
    static int components(const std::string& role);
    /// Packed top-down pixels of `role` at frame `time` and render scale 1 or 0.5 (2x2 box).
    std::vector<float> plane(const std::string& role, double time, double scale) const;
    /// A host clip source for `role`.
    ofxhost::ClipSource source(const std::string& role) const;
};

/// What the reference run through the C API uses.
struct ReferenceOptions {
    std::string method;
    bool temporal = true;
    double scale = 1.0;
    std::vector<std::string>
        aux; ///< bound auxiliary roles (albedo, normal, depth, position, motion)
    std::string floatParam; ///< a float parameter to override ("" = none)
    double floatValue = 0.0;
    /// First frame the history may use: the filter restarts there, and frames before it are
    /// denoised on their own (the plugin's bounded window and start frame).
    double historyStart = -1e9;
    std::string stringParam; ///< a string (choice) parameter to override ("" = none)
    std::string stringValue;
};

/// The weights file the tests give `method`: "" when it runs without one, else the committed
/// test archive (tests/data/afn_parity/weights_full.afnw).
std::string testWeightsFor(const std::string& method);

/// Output of every frame (packed top-down RGBA at the scale) from the afn C API directly.
std::vector<std::vector<float>> referenceFrames(const Sequence& seq, const ReferenceOptions& opt);

} // namespace ofxtest
