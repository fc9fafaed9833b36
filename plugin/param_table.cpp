// SPDX-License-Identifier: Apache-2.0
#include "param_table.h"

#include "ofx_support.h"
#include "param_display.h"

#include <sys/stat.h>

#include <afn/afn.hpp>

#include <algorithm>
#include <cmath>
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

/// The history controls and the mix (version 1.1; after every earlier parameter).
void defineHistoryAndMix(OfxParamSetHandle set)
{
    Props g(define(set, kOfxParamTypeGroup, kGroupHistory));
    g.set(kOfxPropLabel, "History");

    Props frames(defineFixed(set, kOfxParamTypeInteger, kParamHistoryFrames, "History frames",
        "a frame rendered after a jump (scrubbing, a farm chunk) replays at most this many "
        "earlier frames; frames rendered in order continue the history. Above the shot's length: "
        "every frame from the start, exactly as a sequential render"));
    frames.set(kOfxParamPropParent, kGroupHistory);
    frames.set(kOfxParamPropDefault, kDefaultHistoryFrames);
    frames.set(kOfxParamPropMin, 0);
    frames.set(kOfxParamPropMax, 1000000);
    frames.set(kOfxParamPropDisplayMin, 0);
    frames.set(kOfxParamPropDisplayMax, 32);

    Props use(defineFixed(set, kOfxParamTypeBoolean, kParamUseStartFrame, "Limit start",
        "never use frames before Start frame (e.g. a camera cut); off: the history may reach back "
        "to the Source clip's first frame"));
    use.set(kOfxParamPropParent, kGroupHistory);
    use.set(kOfxParamPropDefault, 0);

    Props start(defineFixed(set, kOfxParamTypeInteger, kParamStartFrame, "Start frame",
        "first frame the history may use; frames before it are never read, and a frame before it "
        "is denoised on its own"));
    start.set(kOfxParamPropParent, kGroupHistory);
    start.set(kOfxParamPropDefault, 1);

    Props mix(define(set, kOfxParamTypeDouble, kParamMix));
    mix.set(kOfxPropLabel, "Mix");
    mix.set(kOfxParamPropHint, "blend of the denoised result (1) with Source (0)");
    mix.set(kOfxParamPropDefault, 1.0);
    mix.set(kOfxParamPropMin, 0.0);
    mix.set(kOfxParamPropMax, 1.0);
    mix.set(kOfxParamPropDisplayMin, 0.0);
    mix.set(kOfxParamPropDisplayMax, 1.0);
    mix.set(kOfxParamPropDoubleType, kOfxParamDoubleTypeScale);
}

} // namespace

const ParamCatalog& paramCatalog()
{
    static const ParamCatalog catalog = buildCatalog();
    return catalog;
}

void defineParams(OfxImageEffectHandle descriptor, bool general)
{
    const ParamCatalog& c = paramCatalog();
    OfxParamSetHandle set = nullptr;
    check(suites().effect->getParamSet(descriptor, &set), "getting the parameter set");

    std::vector<std::string> methodLabels;
    std::string methodHint = "denoising method (options follow the library's method list):";
    for (const std::string& m : c.methods) {
        methodLabels.push_back(methodLabel(m));
        const char* d = afnGetFilterTypeDescription(m.c_str());
        methodHint += "\n" + m + ": " + (d ? d : "");
    }
    Props method(defineFixed(set, kOfxParamTypeChoice, kParamMethod, "Method", methodHint));
    method.setStrings(kOfxParamPropChoiceOption, methodLabels);
    method.set(kOfxParamPropDefault, c.defaultMethod);

    Props temporal(defineFixed(set, kOfxParamTypeBoolean, kParamTemporal, "Temporal",
        "use the history of earlier frames (see History frames and Start frame; off: each frame "
        "is denoised on its own)"));
    temporal.set(kOfxParamPropDefault, general ? 1 : 0);

    Props weights(defineFixed(set, kOfxParamTypeString, kParamWeights, "Weights file",
        "trained weights archive (.afnw) for learned methods such as "
        "afn; empty = the weights built into the library, if any"));
    weights.set(kOfxParamPropStringMode, kOfxParamStringIsFilePath);
    weights.set(kOfxParamPropStringFilePathExists, 1);
    weights.set(kOfxParamPropDefault, "");

    std::string group;
    for (const ParamSpec& p : c.params) {
        const bool hidden = !general && needsAuxInputs(p.info.name, p.method.empty());
        const std::string wanted = p.method.empty() ? "inputs" : p.method;
        if (wanted != group) {
            group = wanted;
            Props g(define(set, kOfxParamTypeGroup, "group_" + group));
            const std::string label = methodLabel(p.method);
            g.set(kOfxPropLabel,
                p.method.empty() ? std::string("Inputs") : label.substr(0, label.find(" (")));
            if (p.method.empty() && !general)
                g.set(kOfxParamPropSecret, 1);
        }
        const AFNParamInfo& i = p.info;
        const char* type = i.type == AFN_PARAM_BOOL ? kOfxParamTypeBoolean
            : i.type == AFN_PARAM_INT               ? kOfxParamTypeInteger
            : i.type == AFN_PARAM_FLOAT             ? kOfxParamTypeDouble
                                                    : kOfxParamTypeChoice;
        Props d(defineFixed(set, type, p.ofxName, i.label, i.help));
        d.set(kOfxParamPropParent, "group_" + group);
        if (hidden)
            d.set(kOfxParamPropSecret, 1);
        const DisplayRange shown = displayRange(i);
        if (i.type == AFN_PARAM_BOOL) {
            d.set(kOfxParamPropDefault, i.defaultValue != 0.0 ? 1 : 0);
        } else if (i.type == AFN_PARAM_INT) {
            d.set(kOfxParamPropDefault, static_cast<int>(i.defaultValue));
            d.set(kOfxParamPropMin, static_cast<int>(i.minValue));
            d.set(kOfxParamPropMax, static_cast<int>(i.maxValue));
            d.set(kOfxParamPropDisplayMin, static_cast<int>(std::floor(shown.min)));
            d.set(kOfxParamPropDisplayMax, static_cast<int>(std::ceil(shown.max)));
        } else if (i.type == AFN_PARAM_FLOAT) {
            d.set(kOfxParamPropDefault, i.defaultValue);
            d.set(kOfxParamPropMin, i.minValue);
            d.set(kOfxParamPropMax, i.maxValue);
            d.set(kOfxParamPropDisplayMin, shown.min);
            d.set(kOfxParamPropDisplayMax, shown.max);
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
    std::vector<std::string> deviceLabels;
    for (const char* d : kDeviceOptions)
        deviceLabels.push_back(deviceLabel(d));
    device.setStrings(kOfxParamPropChoiceOption, deviceLabels);
    device.set(kOfxParamPropDefault, 0);

    defineHistoryAndMix(set);
    // Version 1.2: the output choice (General context only: the Pass clip is there).
    Props output(defineFixed(set, kOfxParamTypeChoice, kParamOutputPass, "Output",
        "Beauty: the denoised Source. Pass: the Pass clip (a light-path pass, times PassFactor "
        "when that is connected) denoised with Source, so that the denoised passes add up to the "
        "denoised Source (docs/passes.md)"));
    output.setStrings(kOfxParamPropChoiceOption,
        { "Beauty (the denoised Source)", "Pass (the Pass clip, denoised with Source)" });
    output.set(kOfxParamPropDefault, 0);
    if (!general)
        output.set(kOfxParamPropSecret, 1);
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

void updateParamStates(OfxImageEffectHandle instance, bool general)
{
    const ParamCatalog& c = paramCatalog();
    OfxParamSetHandle set = nullptr;
    check(suites().effect->getParamSet(instance, &set), "getting the parameter set");
    const int m = getIntValue(set, kParamMethod);
    const std::string current = m >= 0 && m < int(c.methods.size()) ? c.methods[m] : "";
    auto props = [&](const std::string& name) {
        OfxParamHandle h = nullptr;
        OfxPropertySetHandle p = nullptr;
        check(suites().param->paramGetHandle(set, name.c_str(), &h, &p), "finding " + name);
        return Props(p);
    };
    std::string group;
    for (const ParamSpec& p : c.params) {
        const bool otherMethod = !p.method.empty() && p.method != current;
        const bool secret
            = otherMethod || (!general && needsAuxInputs(p.info.name, p.method.empty()));
        const std::string g = "group_" + (p.method.empty() ? std::string("inputs") : p.method);
        if (g != group) {
            group = g;
            props(group).set(kOfxParamPropSecret, otherMethod || (!general && p.method.empty()));
        }
        props(p.ofxName).set(kOfxParamPropSecret, secret ? 1 : 0);
    }
    const bool temporal = getIntValue(set, kParamTemporal) != 0;
    props(kParamHistoryFrames).set(kOfxParamPropEnabled, temporal ? 1 : 0);
    props(kParamUseStartFrame).set(kOfxParamPropEnabled, temporal ? 1 : 0);
    props(kParamStartFrame)
        .set(kOfxParamPropEnabled, temporal && getIntValue(set, kParamUseStartFrame) ? 1 : 0);
}

bool affectsParamStates(const std::string& name)
{
    return name == kParamMethod || name == kParamTemporal || name == kParamUseStartFrame;
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
    s.historyFrames = std::max(0, getIntValue(set, kParamHistoryFrames));
    s.useStartFrame = getIntValue(set, kParamUseStartFrame) != 0;
    s.startFrame = getIntValue(set, kParamStartFrame);
    s.outputPass = getIntValue(set, kParamOutputPass) == 1;
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
    os << method << ';' << temporal << ';' << weightsPath << ';' << weightsStamp << ';' << device
       << ";history=" << historyFrames // the start frame is in the runner's key (historyStart)
       << ";output=" << (outputPass ? "pass" : "beauty");
    for (const Value& v : values)
        os << ';' << v.spec->ofxName << '=' << v.number << v.choice;
    return os.str();
}

double readMix(OfxImageEffectHandle instance, double time)
{
    OfxParamSetHandle set = nullptr;
    check(suites().effect->getParamSet(instance, &set), "getting the parameter set");
    double mix = 1.0;
    check(suites().param->paramGetValueAtTime(paramHandle(set, kParamMix), time, &mix),
        "reading parameter mix");
    return std::clamp(mix, 0.0, 1.0);
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
