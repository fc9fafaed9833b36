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

/// Define the method choice, the temporal switch, every catalog parameter and the device choice on
/// a descriptor. `temporalDefault`: default of the temporal switch (off in the Filter context).
void defineParams(OfxImageEffectHandle descriptor, bool temporalDefault);

/// Show the parameters of the instance's current method and hide (kOfxParamPropSecret) the other
/// methods' groups and parameters; called at instance creation and when "method" changes.
void showCurrentMethod(OfxImageEffectHandle instance);

/// The parameter values of an instance that matter for its current method.
struct Settings {
    std::string method;
    bool temporal = true;
    std::string weightsPath; ///< "" = none
    std::string weightsStamp; ///< size and modification time of the file (reload on change)
    std::string device = "cpu"; ///< one of kDeviceOptions
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

/// Set every value of `settings` on a filter (by the library's parameter names).
void applySettings(const Settings& settings, AFNFilter filter);

} // namespace afnofx
