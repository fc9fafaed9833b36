// SPDX-License-Identifier: Apache-2.0
// OFX parameters built from the library's own parameter table (afnGetFilterTypeParam), read back
// from an instance, and applied to an afn filter. No parameter is kept by hand here.
#pragma once

#include "ofx/ofx_api.h"

#include <afn/afn.h>

#include <string>
#include <vector>

namespace afnofx {

/// OFX name of the method choice. Saved projects depend on every OFX name: never rename one.
constexpr const char* kParamMethod = "method";
/// OFX name of the temporal on/off switch.
constexpr const char* kParamTemporal = "temporal";
/// OFX name of the weights file (learned methods; empty = the weights built into the library).
constexpr const char* kParamWeights = "weights";
/// OFX name of the device choice (the last parameter: appended after every other one).
constexpr const char* kParamDevice = "device";
/// Options of the device choice, in order (saved projects store the index).
constexpr const char* kDeviceOptions[] = { "cpu", "cuda", "auto" };
/// The parameters below were added in version 1.1, after "device" (appended, so that every
/// earlier parameter keeps its place).
/// OFX name of the group holding the history controls.
constexpr const char* kGroupHistory = "group_history";
/// OFX name of the history length: a render after a jump replays at most this many frames.
constexpr const char* kParamHistoryFrames = "historyFrames";
/// Default history length (frames). The temporal methods weigh the current frame at least 0.2
/// (alphaMin, SVGF alpha), so older frames fade with 0.8^n: 8 frames keep all but 17% of the
/// steady-state weight and cost 9 frames per jump.
constexpr int kDefaultHistoryFrames = 8;
/// OFX names of the start-frame switch and value: frames before the start frame are never used.
constexpr const char* kParamUseStartFrame = "useStartFrame";
constexpr const char* kParamStartFrame = "startFrame";
/// OFX name of the mix: output = mix * denoised + (1 - mix) * Source. Animates (it does not touch
/// the history).
constexpr const char* kParamMix = "mix";
/// Version 1.2 (after "mix"): what the Output clip shows, the denoised Source or the Pass clip
/// denoised with it (docs/passes.md). Options in order (saved projects store the index).
constexpr const char* kParamOutputPass = "outputPass";
constexpr const char* kOutputPassOptions[] = { "beauty", "pass" };

/// One OFX parameter mirroring one library parameter.
struct ParamSpec {
    std::string ofxName; ///< "<method>_<name>" for a method's own parameter, "<name>" if shared
    std::string method; ///< owning method, "" when every method has it identically
    AFNParamInfo info; ///< the library's description (name, type, default, range, help)
};

/// Every method of the library and the OFX parameters derived from its table.
struct ParamCatalog {
    std::vector<std::string> methods; ///< afnGetFilterTypeName order (the choice's option order)
    int defaultMethod = 0; ///< index into methods
    std::vector<ParamSpec> params;
};

/// The catalog, built once from the library (thread-safe).
const ParamCatalog& paramCatalog();

/// Define the method choice, the temporal switch, every catalog parameter, the device choice, the
/// history controls, the mix and the output choice on a descriptor. `general`: the General context
/// (temporal on by default, auxiliary inputs); in the Filter context the parameters that need
/// auxiliary inputs are defined hidden (kOfxParamPropSecret), so that both contexts keep the same
/// names.
void defineParams(OfxImageEffectHandle descriptor, bool general);

/// Show the parameters of the instance's current method and hide (kOfxParamPropSecret) the other
/// methods' groups and parameters, and in the Filter context those that need auxiliary inputs;
/// enable the history controls only where they act (temporal on; start frame when switched on).
/// Called at instance creation and when "method", "temporal" or "useStartFrame" change.
void updateParamStates(OfxImageEffectHandle instance, bool general);

/// True when a change of the named parameter changes which parameters are shown or enabled.
bool affectsParamStates(const std::string& name);

/// The parameter values of an instance that matter for its current method.
struct Settings {
    std::string method;
    bool temporal = true;
    std::string weightsPath; ///< "" = none
    std::string weightsStamp; ///< size and modification time of the file (reload on change)
    std::string device = "cpu"; ///< one of kDeviceOptions
    int historyFrames = kDefaultHistoryFrames; ///< frames replayed at most before a requested one
    bool useStartFrame = false;
    int startFrame = 1; ///< first frame the history may use (when useStartFrame)
    bool outputPass = false; ///< the Output shows the Pass clip denoised with Source
    struct Value {
        const ParamSpec* spec;
        double number; ///< bool/int/float value
        std::string choice; ///< string value
    };
    std::vector<Value> values;
    /// Text that identifies these settings (cache key).
    std::string key() const;
};

/// Read the instance's settings (parameters do not animate, so no time is needed).
Settings readSettings(OfxImageEffectHandle instance);

/// The mix at `time` (it animates): 1 = the denoised frame, 0 = Source.
double readMix(OfxImageEffectHandle instance, double time);

/// Set every value of `settings` on a filter (by the library's parameter names).
void applySettings(const Settings& settings, AFNFilter filter);

} // namespace afnofx
