// SPDX-License-Identifier: Apache-2.0
// What the plugin tests share: a loaded test host with both context descriptors and the synthetic
// sequence's clips, instances with a method set, whole-frame renders, and the comparison with the
// C API reference.
#pragma once

#include "ofx_test_host.h"
#include "synthetic_sequence.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ofxtest {

/// Auxiliary roles and the General context's clips that carry them, in the same order.
extern const std::vector<std::string> kAllAux;
extern const char* const kClipOf[5];

/// Every method except identity (identity alone when the library has nothing else).
std::vector<std::string> methodsUnderTest();
/// Index of a method in the library's list (the method choice's option index).
int methodIndex(const std::string& m);

/// |got - want| <= 1e-5 * max(|want|, 1e-3) everywhere (relative, with a floor near zero).
::testing::AssertionResult nearlyEqual(
    const std::vector<float>& got, const std::vector<float>& want);

/// OFX name of a library parameter of `method` ("<method>_<name>" or the shared "<name>").
std::string ofxName(const OfxImageEffectStruct& desc, const std::string& method, std::string name);

/// A loaded host with both context descriptors and a source per role of `seq`.
struct Session {
    explicit Session(ofxhost::Layout layout = {}, Sequence sequence = {});
    ~Session();

    /// An instance with Source and the given auxiliary roles connected, running `method`.
    std::unique_ptr<OfxImageEffectStruct> instance(
        const std::string& method, const std::vector<std::string>& aux, bool general = true);
    /// Whole frame (or stitched tiles) at `t`; expects success.
    std::vector<float> render(
        OfxImageEffectStruct* inst, double t, double scale = 1.0, int tiles = 1);

    ofxhost::Host host;
    bool loaded = false;
    Sequence seq;
    std::map<std::string, ofxhost::ClipSource> sources;
    std::unique_ptr<OfxImageEffectStruct> general, filter;
};

} // namespace ofxtest
