// SPDX-License-Identifier: Apache-2.0
#include "param_table.h"

#include "ofx_support.h"

#include <sys/stat.h>

#include <afn/afn.hpp>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <sstream>

namespace afnofx {

namespace {

// Parameters the plugin sets itself from what the host tells it: OFX rows run bottom-up, so the
// y-up pixel vectors of the Motion clip (OFX and Blender convention) set the motion y-up
// convention; pixel vectors shrink with the render scale, which becomes the motion scale.
bool setByPlugin(const char* name)
{
    return std::strcmp(name, AFN_CONVENTION_MOTION_Y_UP) == 0
        || std::strcmp(name, AFN_CONVENTION_MOTION_SCALE) == 0;
}

// Methods in order of preference for the default (the issue asks for AFN once it exists, then
// SVGF, then another temporal method); anything else falls back to the first method.
const char* const kPreferred[] = { "afn", "svgf", "ta", "bmfr" };

bool sameInfo(const AFNParamInfo& a, const AFNParamInfo& b)
{
    return a.type == b.type && a.defaultValue == b.defaultValue && a.minValue == b.minValue
        && a.maxValue == b.maxValue && std::strcmp(a.defaultString, b.defaultString) == 0
        && std::strcmp(a.choices, b.choices) == 0;
}

std::string ofxSafe(std::string s)
{
    std::replace(s.begin(), s.end(), '.', '_');
    return s;
}

ParamCatalog buildCatalog()
{
    ParamCatalog c;
    for (int i = 0, n = afnGetNumFilterTypes(); i < n; ++i)
        c.methods.push_back(afnGetFilterTypeName(i));
    c.defaultMethod = 0;
    for (const char* p : kPreferred) {
        auto it = std::find(c.methods.begin(), c.methods.end(), p);
        if (it != c.methods.end() && afn::isFilterTypeReady(p)) {
            c.defaultMethod = static_cast<int>(it - c.methods.begin());
            break;
        }
    }
    std::vector<std::vector<AFNParamInfo>> tables;
    for (const std::string& m : c.methods) {
        std::vector<AFNParamInfo> t;
        for (int i = 0, n = afnGetFilterTypeNumParams(m.c_str()); i < n; ++i) {
            AFNParamInfo info {};
            if (afnGetFilterTypeParam(m.c_str(), i, &info) && !setByPlugin(info.name))
                t.push_back(info);
        }
        tables.push_back(std::move(t));
    }
    // A parameter every method has with the same description is shared (one OFX parameter);
    // any other one belongs to its method and is prefixed with the method's name.
    auto sharedByAll = [&](const AFNParamInfo& info) {
        for (const auto& t : tables) {
            auto it = std::find_if(t.begin(), t.end(),
                [&](const AFNParamInfo& o) { return std::strcmp(o.name, info.name) == 0; });
            if (it == t.end() || !sameInfo(*it, info))
                return false;
        }
        return true;
    };
    for (size_t m = 0; m < tables.size(); ++m)
        for (const AFNParamInfo& info : tables[m]) {
            if (!sharedByAll(info))
                c.params.push_back({ ofxSafe(c.methods[m] + "_" + info.name), c.methods[m], info });
        }
    if (!tables.empty())
        for (const AFNParamInfo& info : tables[0])
            if (sharedByAll(info))
                c.params.push_back({ ofxSafe(info.name), "", info });
    return c;
}

OfxPropertySetHandle define(OfxParamSetHandle set, const char* type, const std::string& name)
{
    OfxPropertySetHandle props = nullptr;
    check(
        suites().param->paramDefine(set, type, name.c_str(), &props), "defining parameter " + name);
    return props;
}

/// A parameter that never animates (the result at t replays the frames before t with one
/// setting), with its label and hint.
OfxPropertySetHandle defineFixed(OfxParamSetHandle set, const char* type, const std::string& name,
    const std::string& label, const std::string& hint)
{
    Props p(define(set, type, name));
    p.set(kOfxPropLabel, label);
    p.set(kOfxParamPropHint, hint);
    p.set(kOfxParamPropAnimates, 0);
    return p.handle();
}

} // namespace

const ParamCatalog& paramCatalog()
{
    static const ParamCatalog catalog = buildCatalog();
    return catalog;
}

void defineParams(OfxImageEffectHandle descriptor, bool temporalDefault)
{
    const ParamCatalog& c = paramCatalog();
    OfxParamSetHandle set = nullptr;
    check(suites().effect->getParamSet(descriptor, &set), "getting the parameter set");

    Props method(defineFixed(set, kOfxParamTypeChoice, kParamMethod, "Method",
        "denoising method (options follow the library's method list)"));
    method.setStrings(kOfxParamPropChoiceOption, c.methods);
    method.set(kOfxParamPropDefault, c.defaultMethod);

    Props temporal(defineFixed(set, kOfxParamTypeBoolean, kParamTemporal, "Temporal",
        "use the history of every frame from the clip's first frame "
        "(off: each frame is denoised on its own)"));
    temporal.set(kOfxParamPropDefault, temporalDefault ? 1 : 0);

    Props weights(defineFixed(set, kOfxParamTypeString, kParamWeights, "Weights file",
        "trained weights archive (.afnw) for learned methods such as "
        "afn; empty = the weights built into the library, if any"));
    weights.set(kOfxParamPropStringMode, kOfxParamStringIsFilePath);
    weights.set(kOfxParamPropStringFilePathExists, 1);
    weights.set(kOfxParamPropDefault, "");

    std::string group;
    for (const ParamSpec& p : c.params) {
        const std::string wanted = p.method.empty() ? "inputs" : p.method;
        if (wanted != group) {
            group = wanted;
            Props g(define(set, kOfxParamTypeGroup, "group_" + group));
            g.set(kOfxPropLabel, p.method.empty() ? std::string("Inputs") : p.method);
        }
        const AFNParamInfo& i = p.info;
        const char* type = i.type == AFN_PARAM_BOOL ? kOfxParamTypeBoolean
            : i.type == AFN_PARAM_INT               ? kOfxParamTypeInteger
            : i.type == AFN_PARAM_FLOAT             ? kOfxParamTypeDouble
                                                    : kOfxParamTypeChoice;
        Props d(defineFixed(set, type, p.ofxName, i.label, i.help));
        d.set(kOfxParamPropParent, "group_" + group);
        if (i.type == AFN_PARAM_BOOL) {
            d.set(kOfxParamPropDefault, i.defaultValue != 0.0 ? 1 : 0);
        } else if (i.type == AFN_PARAM_INT) {
            d.set(kOfxParamPropDefault, static_cast<int>(i.defaultValue));
            d.set(kOfxParamPropMin, static_cast<int>(i.minValue));
            d.set(kOfxParamPropMax, static_cast<int>(i.maxValue));
            d.set(kOfxParamPropDisplayMin, static_cast<int>(i.minValue));
            d.set(kOfxParamPropDisplayMax, static_cast<int>(i.maxValue));
        } else if (i.type == AFN_PARAM_FLOAT) {
            d.set(kOfxParamPropDefault, i.defaultValue);
            d.set(kOfxParamPropMin, i.minValue);
            d.set(kOfxParamPropMax, i.maxValue);
            d.set(kOfxParamPropDisplayMin, i.minValue);
            d.set(kOfxParamPropDisplayMax, i.maxValue);
            d.set(kOfxParamPropDoubleType, kOfxParamDoubleTypePlain);
        } else {
            const std::vector<std::string> options = afn::splitChoices(i.choices);
            d.setStrings(kOfxParamPropChoiceOption, options);
            auto it = std::find(options.begin(), options.end(), i.defaultString);
            d.set(kOfxParamPropDefault, it == options.end() ? 0 : int(it - options.begin()));
        }
    }

    // Last, so that the parameters above keep their places in saved projects.
    Props device(defineFixed(set, kOfxParamTypeChoice, kParamDevice, "Device",
        "where the filter runs: cpu (the reference results, the same on every machine), cuda (an "
        "NVIDIA GPU of compute capability 9.0 or newer, in builds with CUDA; only afn runs there, "
        "in half precision within the documented tolerance of cpu), auto (cuda when there is one "
        "and the method runs there, else cpu with a note in the host's log)"));
    device.setStrings(kOfxParamPropChoiceOption,
        std::vector<std::string>(std::begin(kDeviceOptions), std::end(kDeviceOptions)));
    device.set(kOfxParamPropDefault, 0);
}

static OfxParamHandle paramHandle(OfxParamSetHandle set, const std::string& name)
{
    OfxParamHandle h = nullptr;
    check(suites().param->paramGetHandle(set, name.c_str(), &h, nullptr),
        "finding parameter " + name);
    return h;
}

static int getIntValue(OfxParamSetHandle set, const std::string& name)
{
    int v = 0;
    check(suites().param->paramGetValue(paramHandle(set, name), &v), "reading parameter " + name);
    return v;
}

void showCurrentMethod(OfxImageEffectHandle instance)
{
    const ParamCatalog& c = paramCatalog();
    OfxParamSetHandle set = nullptr;
    check(suites().effect->getParamSet(instance, &set), "getting the parameter set");
    const int m = getIntValue(set, kParamMethod);
    const std::string current = m >= 0 && m < int(c.methods.size()) ? c.methods[m] : "";
    auto hide = [&](const std::string& name, bool secret) {
        OfxParamHandle h = nullptr;
        OfxPropertySetHandle props = nullptr;
        check(suites().param->paramGetHandle(set, name.c_str(), &h, &props), "finding " + name);
        Props(props).set(kOfxParamPropSecret, secret ? 1 : 0);
    };
    std::string group;
    for (const ParamSpec& p : c.params) {
        if (p.method.empty())
            continue;
        const bool secret = p.method != current;
        if (p.method != group) {
            group = p.method;
            hide("group_" + group, secret);
        }
        hide(p.ofxName, secret);
    }
}

Settings readSettings(OfxImageEffectHandle instance)
{
    const ParamCatalog& c = paramCatalog();
    OfxParamSetHandle set = nullptr;
    check(suites().effect->getParamSet(instance, &set), "getting the parameter set");
    Settings s;
    const int m = getIntValue(set, kParamMethod);
    if (m < 0 || m >= static_cast<int>(c.methods.size()))
        throw OfxError(kOfxStatErrValue, "method index " + std::to_string(m) + " is out of range");
    s.method = c.methods[m];
    s.temporal = getIntValue(set, kParamTemporal) != 0;
    const int device = getIntValue(set, kParamDevice);
    if (device < 0 || device >= static_cast<int>(std::size(kDeviceOptions)))
        throw OfxError(
            kOfxStatErrValue, "device index " + std::to_string(device) + " is out of range");
    s.device = kDeviceOptions[device];
    char* path = nullptr;
    check(suites().param->paramGetValue(paramHandle(set, kParamWeights), &path),
        "reading parameter weights");
    s.weightsPath = path ? path : "";
    struct stat st { };
    if (!s.weightsPath.empty() && ::stat(s.weightsPath.c_str(), &st) == 0)
        s.weightsStamp = std::to_string(st.st_size) + "@" + std::to_string(st.st_mtime);
    for (const ParamSpec& p : c.params) {
        if (!p.method.empty() && p.method != s.method)
            continue;
        Settings::Value v { &p, 0.0, {} };
        if (p.info.type == AFN_PARAM_FLOAT) {
            check(suites().param->paramGetValue(paramHandle(set, p.ofxName), &v.number),
                "reading parameter " + p.ofxName);
        } else if (p.info.type == AFN_PARAM_STRING) {
            const std::vector<std::string> options = afn::splitChoices(p.info.choices);
            const int index = getIntValue(set, p.ofxName);
            if (index < 0 || index >= static_cast<int>(options.size()))
                throw OfxError(kOfxStatErrValue, "parameter " + p.ofxName + " index out of range");
            v.choice = options[index];
        } else {
            v.number = getIntValue(set, p.ofxName);
        }
        s.values.push_back(std::move(v));
    }
    return s;
}

std::string Settings::key() const
{
    std::ostringstream os;
    os.precision(17);
    os << method << ';' << temporal << ';' << weightsPath << ';' << weightsStamp << ';' << device;
    for (const Value& v : values)
        os << ';' << v.spec->ofxName << '=' << v.number << v.choice;
    return os.str();
}

void applySettings(const Settings& settings, AFNFilter filter)
{
    for (const Settings::Value& v : settings.values) {
        const char* name = v.spec->info.name;
        switch (v.spec->info.type) {
        case AFN_PARAM_BOOL:
            afnSetFilterBool(filter, name, v.number != 0.0);
            break;
        case AFN_PARAM_INT:
            afnSetFilterInt(filter, name, static_cast<int>(v.number));
            break;
        case AFN_PARAM_FLOAT:
            afnSetFilterFloat(filter, name, static_cast<float>(v.number));
            break;
        case AFN_PARAM_STRING:
            afnSetFilterString(filter, name, v.choice.c_str());
            break;
        }
    }
}

} // namespace afnofx
