// SPDX-License-Identifier: Apache-2.0
// A small in-process OpenFX host for the plugin tests: loads a binary with dlopen and offers the
// property, image-effect, parameter, memory, multithread and message suites with time support,
// tiles, render scales and configurable image layouts (bottom-up or negative row bytes, padding).
#pragma once

#include "ofx/ofx_api.h"

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace ofxhost {

/// One property: a typed array of values.
struct Prop {
    enum Type { Int, Double, String, Pointer } type = Int;
    std::vector<int> i;
    std::vector<double> d;
    std::vector<std::string> s;
    std::vector<void*> p;
};

class Host;

} // namespace ofxhost

/// Property set (the host's definition of the opaque OFX handle type).
struct OfxPropertySetStruct {
    std::map<std::string, ofxhost::Prop> props;
    std::shared_ptr<void> owned; ///< image memory owned by an image property set
    ofxhost::Host* imageHost = nullptr; ///< the host that handed this image out

    void setInts(const std::string& name, std::vector<int> v);
    void setDoubles(const std::string& name, std::vector<double> v);
    void setStrings(const std::string& name, std::vector<std::string> v);
    void setPointer(const std::string& name, void* v);
    bool has(const std::string& name) const { return props.count(name) != 0; }
    /// Typed reads for the tests; throw std::out_of_range when missing.
    int getInt(const std::string& name, int index = 0) const;
    double getDouble(const std::string& name, int index = 0) const;
    const std::string& getString(const std::string& name, int index = 0) const;
    const std::vector<std::string>& getStrings(const std::string& name) const;
    void* getPointer(const std::string& name, int index = 0) const;
};

/// One parameter (descriptor or instance) with its current value.
struct OfxParamStruct {
    OfxPropertySetStruct props;
    std::string type;
    std::string name;
    int intValue = 0; ///< boolean, integer and choice parameters
    double doubleValue = 0; ///< double parameters
    std::string stringValue; ///< string parameters
};

/// The parameters of a descriptor or instance, in definition order.
struct OfxParamSetStruct {
    OfxPropertySetStruct props;
    std::vector<std::unique_ptr<OfxParamStruct>> params;
    OfxParamStruct* find(const std::string& name) const;
};

namespace ofxhost {

struct ClipSource;

} // namespace ofxhost

/// A clip of a descriptor or instance.
struct OfxImageClipStruct {
    OfxPropertySetStruct props;
    std::string name;
    const ofxhost::ClipSource* source = nullptr; ///< instance input clips only (NULL: unconnected)
    struct OfxImageEffectStruct* effect = nullptr;
    std::mutex framesMutex;
    std::vector<double> framesNeeded; ///< last GetFramesNeeded answer (for the tests to inspect)
    std::vector<double> lastRoI; ///< last GetRegionsOfInterest answer, empty = default
    std::vector<double> fetched; ///< times of every image fetched from this input clip, in order
    /// Fetched times since the last call, and forget them (guarded by framesMutex).
    std::vector<double> takeFetched();
};

/// An effect descriptor or instance.
struct OfxImageEffectStruct {
    OfxPropertySetStruct props;
    OfxParamSetStruct params;
    std::vector<std::unique_ptr<OfxImageClipStruct>> clips;
    ofxhost::Host* host = nullptr;
    OfxImageClipStruct* clip(const std::string& name) const;
};

namespace ofxhost {

/// Pixels an input clip provides: a full-resolution frame of `width` x `height` pixels whose region
/// of definition starts at canonical (originX, originY) (even numbers, so that scale 0.5 stays on
/// whole pixels).
struct ClipSource {
    int width = 0, height = 0;
    int components = 4; ///< 4 RGBA, 3 RGB, 1 Alpha
    int originX = 0, originY = 0;
    double firstFrame = 0, lastFrame = 0;
    /// Packed top-down pixels of frame `time` at render `scale` (1 or 0.5: 2x2 box filter);
    /// false when the clip has no such frame.
    std::function<bool(double time, double scale, std::vector<float>& pixels)> frame;
};

/// How the host lays out the images it hands out.
struct Layout {
    bool negativeRowBytes = false; ///< top-down memory with negative row bytes
    int rowPaddingPixels = 0; ///< unused pixels at the end of every row
};

/// A rendered output frame: packed top-down RGBA over the output's pixel region of definition.
struct Frame {
    OfxRectI bounds {};
    std::vector<float> rgba;
};

class Host {
public:
    explicit Host(Layout layout = {});
    ~Host();

    /// dlopen the binary and find the plugin; false with a message in *error on failure.
    bool load(const std::string& path, std::string* error);
    OfxPlugin* plugin() const { return m_plugin; }
    int numPlugins() const { return m_numPlugins; }

    /// Call the plugin's main entry.
    OfxStatus action(const char* action, const void* handle, OfxPropertySetStruct* inArgs,
        OfxPropertySetStruct* outArgs);
    /// setHost, Load and Describe; the descriptor is kept.
    OfxStatus describe();
    OfxImageEffectStruct* descriptor() const { return m_descriptor.get(); }
    /// DescribeInContext on a fresh copy of the descriptor.
    OfxStatus describeInContext(
        const std::string& context, std::unique_ptr<OfxImageEffectStruct>& out);
    /// CreateInstance from a context descriptor; `inputs` maps clip names to sources (not owned).
    std::unique_ptr<OfxImageEffectStruct> createInstance(
        const OfxImageEffectStruct& contextDescriptor, const std::string& context,
        const std::map<std::string, const ClipSource*>& inputs, OfxStatus* status);
    OfxStatus destroyInstance(OfxImageEffectStruct* instance);
    /// Unload and dlclose.
    OfxStatus unload();

    /// Set a parameter value (int for boolean/integer/choice) and send InstanceChanged.
    OfxStatus setParam(OfxImageEffectStruct* instance, const std::string& name, double value);
    /// Set a string parameter and send InstanceChanged.
    OfxStatus setParam(
        OfxImageEffectStruct* instance, const std::string& name, const std::string& value);

    /// Render frame `time` at `scale` as a host does: RoD, RoI, frames needed, then one Render
    /// per tile (`tiles` x `tiles`, uneven split), stitched into `out`. Returns the first failure.
    OfxStatus renderFrame(
        OfxImageEffectStruct* instance, double time, double scale, int tiles, Frame& out);

    /// Ask renders to abort (the image-effect suite's abort answers this).
    std::atomic<bool> abortFlag { false };
    /// Messages posted through the message suite ("type: text").
    std::vector<std::string> messages() const;
    /// Images handed out and not yet released.
    int liveImages() const { return m_liveImages.load(); }

    // ---- used by the suite implementations --------------------------------------------------
    Layout layout() const { return m_layout; }
    void addMessage(const std::string& m);
    std::atomic<int> m_liveImages { 0 };
    OfxPropertySetStruct hostProps;

private:
    Layout m_layout;
    void* m_library = nullptr;
    OfxPlugin* m_plugin = nullptr;
    int m_numPlugins = 0;
    OfxHost m_ofxHost {};
    std::unique_ptr<OfxImageEffectStruct> m_descriptor;
    mutable std::mutex m_messagesMutex;
    std::vector<std::string> m_messages;
};

/// The host's suite lookup (fetchSuite).
const void* fetchSuite(OfxPropertySetHandle host, const char* name, int version);

/// Build an image property set for `bounds` (pixel coordinates at `scale`) from a packed
/// top-down frame covering `frameBounds`, laid out as `layout` says; the set owns its memory.
OfxPropertySetStruct* makeImage(const std::vector<float>* frame, const OfxRectI& frameBounds,
    const OfxRectI& bounds, int components, double scale, const Layout& layout);
/// The render target of the calling thread while a Render action runs.
struct RenderTarget {
    OfxImageEffectStruct* instance = nullptr;
    double time = 0, scale = 1;
    OfxRectI window {};
    OfxPropertySetStruct* image = nullptr; ///< the Output image (owned by the render call)
    /// GetFramesNeeded answer of this render per clip (pairs); the host refuses other times.
    std::map<std::string, std::vector<double>> framesNeeded;
};
RenderTarget*& currentRenderTarget();

} // namespace ofxhost
